// Test-only: drives a SimPrinter (the firmware's C++ as WebAssembly) in virtual time like a
// one-line-at-a-time host, collecting its lines.

import { encodeFrame } from '../protocol/dialect-frame';
import { SimPrinter, type SimOptions } from './sim-printer';

export class SimHost {
  readonly sim: SimPrinter;
  /** Every line the printer sent, and when each came (µs of the printer's time). */
  readonly lines: string[] = [];
  readonly times: number[] = [];
  #partial = '';
  #n = 0;

  /** `boot` false leaves the power-up to the test (a printer that runs on before its host comes). */
  constructor(options: SimOptions = {}, boot = true) {
    this.sim = new SimPrinter((bytes) => {
      const parts = (this.#partial + bytes).split('\n');
      this.#partial = parts.pop()!;
      this.lines.push(...parts);
      for (const _ of parts) this.times.push(this.sim.clock.now);
    }, options);
    if (boot) this.boot();
  }

  /** Opens the port: the Mega restarts, and its `start` comes a tenth of a second later. */
  boot(): void {
    this.sim.boot();
    this.waitFor(/^start$/, 1000, false);
  }

  /**
   * Sends one numbered line and runs virtual time until its `ok`; returns the lines of its reply
   * block, without the `busy:` keepalives a long command sends meanwhile.
   */
  cmd(body: string, maxMs = 600_000): string[] {
    const from = this.lines.length;
    this.#n++;
    const plain = body.startsWith('M110');
    this.sim.receive((plain ? body : encodeFrame(this.#n, body)) + '\n');
    const mine = (l: string) => (plain ? l.startsWith('ok') : l.startsWith(`ok N${this.#n} `));
    for (let t = 0; t < maxMs; t += 1) {
      const ok = this.lines.findIndex((l, i) => i >= from && mine(l));
      if (ok >= 0) return this.lines.slice(from, ok + 1).filter((l) => !l.startsWith('busy:'));
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

  /**
   * Runs virtual time until a line matches, or fails. Meanwhile it asks M105 every 2 s, as hosts
   * do: the Mega pauses a job when no host has said anything for 30 s (mega.md §6).
   */
  waitFor(pattern: RegExp, maxMs = 600_000, poll = true): string {
    const from = this.lines.length;
    for (let t = 0; t <= maxMs; t += 5) {
      for (let i = from; i < this.lines.length; i++) if (pattern.test(this.lines[i])) return this.lines[i];
      if (poll && t % 2000 === 1995) this.sim.receive(encodeFrame(++this.#n, 'M105') + '\n');
      this.sim.advance(5);
    }
    throw new Error(`no line like ${pattern} within ${maxMs} ms`);
  }
}

/** How long a paced job waited for the head to cool: between each `JOB:` line with `cooling=1` and the next without it. */
export function cooledUs(h: SimHost): number {
  let total = 0;
  let since: number | null = null;
  h.lines.forEach((l, i) => {
    if (!l.startsWith('JOB:')) return;
    const cooling = / cooling=1/.test(l);
    if (cooling && since === null) since = h.times[i];
    if (!cooling && since !== null) {
      total += h.times[i] - since;
      since = null;
    }
  });
  return total;
}
