// A host Transport on a SimPrinter, in the printer's virtual time. The printer's module carries the
// bytes at 115200 baud itself (the Mega's UART, mega_rig.h); this adds the one-way latency of what
// is between (a USB frame, the ESP's bridge).

import type { Transport } from '../device/transport';
import type { ClientOptions } from '../device/dialect-client';
import { SimPrinter, type SimOptions } from './sim-printer';

export interface WireOptions {
  /** One-way latency in µs (USB frames, the ESP bridge...). */
  latencyUs?: number;
}

export class SimWire {
  readonly printer: SimPrinter;
  readonly host: Transport;
  /** Client options whose clock and timers are the printer's virtual clock. */
  readonly clientOptions: ClientOptions;
  #latency: number;
  #onBytes: (b: string) => void = () => {};
  #onClosed: (e?: Error) => void = () => {};
  /** Bytes carried each way. */
  carried = { toPrinter: 0, toHost: 0 };

  constructor(sim: SimOptions = {}, wire: WireOptions = {}) {
    this.#latency = wire.latencyUs ?? 1000;
    this.printer = new SimPrinter((bytes) => this.#carry(bytes, 'toHost'), sim);
    this.printer.onDisconnect = () => this.#onClosed(new Error('device lost'));
    const self = this;
    this.host = {
      kind: 'serial',
      async open(onBytes, onClosed) {
        self.#onBytes = onBytes;
        self.#onClosed = onClosed;
        self.printer.boot();
      },
      async send(bytes) {
        self.#carry(bytes, 'toPrinter');
      },
      async close() {},
    };
    const clock = () => this.printer.clock;
    this.clientOptions = {
      now: () => clock().now / 1000,
      setTimer: (fn, ms) => clock().after(ms * 1000, fn),
      clearTimer: (t) => clock().cancel(t as Parameters<ReturnType<typeof clock>['cancel']>[0]),
    };
  }

  #carry(bytes: string, dir: 'toPrinter' | 'toHost'): void {
    this.carried[dir] += bytes.length;
    this.printer.clock.after(this.#latency, () => (dir === 'toPrinter' ? this.printer.receive(bytes) : this.#onBytes(bytes)));
  }

  /** Runs virtual time until `done` or `maxMs` passes; true if done. */
  runUntil(done: () => boolean, maxMs: number): boolean {
    const end = this.printer.clock.now + maxMs * 1000;
    while (!done()) {
      const next = this.printer.clock.next;
      if (next === Infinity || next > end) {
        this.printer.advanceTo(end);
        return done();
      }
      this.printer.advanceTo(next);
    }
    return true;
  }
}
