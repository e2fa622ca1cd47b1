// The firmware-as-WebAssembly printer as a serial device for desktop hosts (npm run sim --
// --firmware): a host's bytes in, the Mega's lines out, its time kept with the host's clock.
import type { PrinterModule } from './printer-module';

/** How much of the machine's time runs before its output is passed on: 10 ms, a USB frame or ten. */
const SLICE_US = 10_000;

export class FirmwareSerial {
  #us = 0;
  #booted = false;

  constructor(private readonly module: PrinterModule, private readonly emit: (bytes: string) => void) {}

  /** Power-up. */
  boot(): void {
    this.module.start();
    this.#booted = true;
  }

  /** The Mega restarts, as when a host opens its USB port: the card and EEPROM are kept. */
  resetMega(): void {
    this.module.reset();
  }

  receive(bytes: string): void {
    this.module.receive(0, Uint8Array.from(bytes, (c) => c.charCodeAt(0) & 0xff));
  }

  /** Runs the machine up to `ms` of its own time since it started, passing its lines on as they come. */
  tick(ms: number): void {
    const target = Math.floor(ms * 1000);
    if (!this.#booted) {
      this.#us = target;  // no power yet: its time starts when it boots
      return;
    }
    while (this.#us < target) {
      const step = Math.min(target - this.#us, SLICE_US);
      this.module.run(step);
      this.#us += step;
      const lines = this.module.sent(0);
      if (lines.length) this.emit(lines.map((l) => l + '\n').join(''));
    }
  }
}
