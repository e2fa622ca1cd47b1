// Test-only: a SimPrinter running in Node against the wall clock (times `speed`), for the transports' peers.
import { SimPrinter, type SimOptions } from '../app/src/sim/sim-printer';

export class NodeSim {
  readonly printer: SimPrinter;
  #timer: ReturnType<typeof setInterval>;
  #sink: (bytes: string) => void = () => {};

  constructor(options: SimOptions = {}, speed = 1) {
    this.printer = new SimPrinter((bytes) => this.#sink(bytes), options);
    const start = Date.now();
    this.#timer = setInterval(() => this.printer.tick((Date.now() - start) * speed), 10);
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
