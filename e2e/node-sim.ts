// Test-only: a SimPrinter (the firmware's C++ as WebAssembly) running in Node against the wall clock
// (times `speed`), for the transports' peers.
import '../app/src/sim/wasm/node-firmware';
import { SimPrinter, type SimOptions } from '../app/src/sim/sim-printer';

export class NodeSim {
  readonly printer: SimPrinter;
  #timer: ReturnType<typeof setInterval>;
  #sink: (bytes: string) => void = () => {};

  constructor(options: SimOptions = {}, speed = 1) {
    this.printer = new SimPrinter((bytes) => this.#sink(bytes), options);
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

  /** Opening the port resets a real Mega: it boots and prints `start`. */
  open(): void {
    this.printer.boot();
  }

  connect(sink: (bytes: string) => void): void {
    this.attach(sink);
    this.open();
  }

  receive(bytes: string): void {
    this.printer.receive(bytes);
  }

  stop(): void {
    clearInterval(this.#timer);
  }
}
