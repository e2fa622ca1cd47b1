// A simulated serial wire between a host Transport and a SimPrinter, in the printer's virtual time:
// each direction carries one byte per byte-time (10 bits at the baud rate) after a fixed latency.

import type { Transport } from '../device/transport';
import type { ClientOptions } from '../device/dialect-client';
import { SimPrinter, type SimOptions } from './sim-printer';

export interface WireOptions {
  baud?: number;
  /** One-way latency in µs (USB frames, the ESP bridge...). */
  latencyUs?: number;
}

export class SimWire {
  readonly printer: SimPrinter;
  readonly host: Transport;
  /** Client options whose clock and timers are the printer's virtual clock. */
  readonly clientOptions: ClientOptions;
  #byteUs: number;
  #latency: number;
  #toPrinterFree = 0;
  #toHostFree = 0;
  #onBytes: (b: string) => void = () => {};
  #onClosed: (e?: Error) => void = () => {};
  /** Bytes carried each way. */
  carried = { toPrinter: 0, toHost: 0 };

  constructor(sim: SimOptions = {}, wire: WireOptions = {}) {
    this.#byteUs = 1e7 / (wire.baud ?? 115200);
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
    const clock = this.printer.clock;
    for (let i = 0; i < bytes.length; i++) {
      const free = dir === 'toPrinter' ? this.#toPrinterFree : this.#toHostFree;
      const doneAt = Math.max(free, clock.now) + this.#byteUs;
      if (dir === 'toPrinter') this.#toPrinterFree = doneAt;
      else this.#toHostFree = doneAt;
      const c = bytes[i];
      this.carried[dir]++;
      clock.at(doneAt + this.#latency, () => (dir === 'toPrinter' ? this.printer.receive(c) : this.#onBytes(c)));
    }
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
