// The firmware-as-WebAssembly printer on a host Transport, in virtual time: the app's device layer
// (DialectLink) talks to the Mega's own C++ through it. The module models the 115200-baud wire
// itself (mega_rig.h's host port); this side moves its bytes and runs its clock beside the
// client's timers, a millisecond at a time at most.
import type { ClientOptions } from '../../device/dialect-client';
import type { Transport } from '../../device/transport';
import { VirtualClock } from '../clock';
import type { PrinterModule } from './printer-module';

const STEP_US = 1000;
/** The machine's main loop runs every 100 µs (mega_rig.h): its time moves in whole passes. */
const PASS_US = 100;

export class WasmWire {
  readonly clock = new VirtualClock();
  readonly host: Transport;
  /** Client options whose clock and timers are the machine's virtual time. */
  readonly clientOptions: ClientOptions;
  #onBytes: (bytes: string) => void = () => {};

  constructor(readonly printer: PrinterModule) {
    const self = this;
    this.host = {
      kind: 'serial',
      async open(onBytes) {
        self.#onBytes = onBytes;
        self.printer.start(); // opening a Mega's USB port resets it
      },
      async send(bytes) {
        self.printer.receive(0, bytes);
      },
      async close() {},
    };
    this.clientOptions = {
      now: () => this.clock.now / 1000,
      setTimer: (fn, ms) => this.clock.after(ms * 1000, fn),
      clearTimer: (t) => this.clock.cancel(t as object),
    };
  }

  /** Runs the machine and the client's timers together up to `us` from now. */
  advance(us: number): void {
    const end = this.clock.now + us;
    while (this.clock.now < end) {
      // To the client's next timer, in whole passes (a timer may fire up to a pass late).
      const to = Math.min(end, this.clock.now + STEP_US, this.clock.next);
      const step = Math.max(PASS_US, Math.ceil((to - this.clock.now) / PASS_US) * PASS_US);
      this.printer.run(step);
      const lines = this.printer.sent(0);
      if (lines.length) this.#onBytes(lines.map((l) => l + '\n').join(''));
      this.clock.advanceTo(this.clock.now + step);
    }
  }
}
