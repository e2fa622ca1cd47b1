// Test-only: a SimPrinter (the firmware's C++ as WebAssembly) running in Node against the wall clock
// (times `speed`), for the transports' peers. Opened as a USB port, it resets as a Mega does: its
// bootloader waits first, and what the host sends meanwhile is lost.
import '../app/src/sim/wasm/node-firmware';
import { SimPrinter, type SimOptions } from '../app/src/sim/sim-printer';

/** How long a Mega's bootloader waits after a reset before its firmware starts, in wall ms (the host's time). */
export const BOOTLOADER_MS = 1000;

export class NodeSim {
  readonly printer: SimPrinter;
  /** Bytes the host sent while the Mega's bootloader had the port: lost, as on a real board. */
  lost = 0;
  #timer: ReturnType<typeof setInterval>;
  #sink: (bytes: string) => void = () => {};
  #booting: ReturnType<typeof setTimeout> | null = null;

  constructor(options: SimOptions = {}, speed = 1) {
    this.printer = new SimPrinter((bytes) => this.#booting === null && this.#sink(bytes), options);
    let start = Date.now();
    // In slices of at most 40 ms of wall time: a machine slower than asked falls behind rather than hold up the test.
    this.#timer = setInterval(() => {
      const began = Date.now();
      const target = (began - start) * speed;
      const p = this.printer;
      while (p.clock.now / 1000 < target && Date.now() - began < 40) p.tick(Math.min(target, p.clock.now / 1000 + 20 * speed));
      if (p.clock.now / 1000 < target) start = Date.now() - p.clock.now / 1000 / speed;
    }, 10);
  }

  /** Where the printer's bytes go. */
  attach(sink: (bytes: string) => void): void {
    this.#sink = sink;
  }

  /** Opening the port resets a real Mega (DTR): its bootloader waits, then the firmware starts and prints `start`. */
  open(): void {
    if (this.#booting !== null) clearTimeout(this.#booting);
    this.#booting = setTimeout(() => {
      this.#booting = null;
      this.printer.boot();
    }, BOOTLOADER_MS);
  }

  /** The ESP's UART, which does not reset the Mega: here the Mega starts at once. */
  connect(sink: (bytes: string) => void): void {
    this.attach(sink);
    this.printer.boot();
  }

  receive(bytes: string): void {
    if (this.#booting !== null) this.lost += bytes.length;
    else this.printer.receive(bytes);
  }

  stop(): void {
    clearInterval(this.#timer);
    if (this.#booting !== null) clearTimeout(this.#booting);
  }
}
