// Test-only: drives a SimPrinter in virtual time like a one-line-at-a-time host, collecting its lines.

import { encodeFrame } from '../protocol/dialect-frame';
import { SimPrinter, type SimOptions } from './sim-printer';

export class SimHost {
  readonly sim: SimPrinter;
  /** Every line the printer sent. */
  readonly lines: string[] = [];
  #partial = '';
  #n = 0;

  /** `boot` false leaves the power-up to the test (a printer that runs on before its host comes). */
  constructor(options: SimOptions = {}, boot = true) {
    this.sim = new SimPrinter((bytes) => {
      const parts = (this.#partial + bytes).split('\n');
      this.#partial = parts.pop()!;
      this.lines.push(...parts);
    }, options);
    if (boot) this.sim.boot();
  }

  /** Sends one numbered line and runs virtual time until its `ok`; returns the lines of its reply block. */
  cmd(body: string, maxMs = 600_000): string[] {
    const from = this.lines.length;
    this.#n++;
    this.sim.receive((body.startsWith('M110') ? body : encodeFrame(this.#n, body)) + '\n');
    for (let t = 0; t < maxMs; t += 1) {
      const ok = this.lines.findIndex((l, i) => i >= from && l.startsWith('ok'));
      if (ok >= 0) return this.lines.slice(from, ok + 1);
      this.sim.advance(1);
    }
    throw new Error(`no ok for ${body} within ${maxMs} ms`);
  }

  /** Uploads a job file to the card: M28, its records, M29. */
  upload(file: string, text: string): void {
    this.cmd(`M28 ${file}`);
    for (const record of text.trimEnd().split('\n')) this.cmd(record);
    this.cmd('M29');
  }

  /** After the printer resets, its line counter is 0 again: resynchronise as hosts do on reconnect. */
  reconnect(): void {
    this.#n = 0;
    this.cmd('M110 N0');
    this.#n = 0;
  }

  /** Runs virtual time until a line matches, or fails. */
  waitFor(pattern: RegExp, maxMs = 600_000): string {
    const from = this.lines.length;
    for (let t = 0; t <= maxMs; t += 5) {
      const hit = this.lines.slice(from).find((l) => pattern.test(l));
      if (hit) return hit;
      this.sim.advance(5);
    }
    throw new Error(`no line like ${pattern} within ${maxMs} ms`);
  }
}
