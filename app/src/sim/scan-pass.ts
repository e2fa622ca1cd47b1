// One scan pass on the simulated machine (protocol/planner.md "Scan mode"), run as the Mega runs it
// through the printhead (protocol/nano.md "Scan programs"): the pass's events go to the Nano as a
// chain of programs, two before the head moves and the rest as buffers free up; the head
// accelerates from rest at its run-up; the `G` goes out 1000 µs before the start mark, so the
// Nano's time 0 is the mark; the Nano switches the LEDs on its own clock while the head crosses at
// the speed; a `Q` poll every 10 ms keeps the chain alive and tells how it ended.

import { passDurationUs } from '../planner/job-plan';
import type { ScanPlan } from '../planner/scan';
import { parseNanoReply } from '../protocol/nano';
import { PROGRAM_START_LEAD_US, programLines } from '../protocol/scan-program';
import type { Clock } from './clock';
import type { NanoModel } from './nano-model';
import { PASS } from './nano-programs';

export interface ScanExposure {
  pass: number;
  hy: number;
  descending: boolean;
  /** Per LED 0-3: [on, off] µs after the pass's start mark, as the printhead switched them. */
  leds: [number, number][][];
}

export interface ScanPassHooks {
  /** The head's move across, from run-up to run-out, taking `us`. */
  moveUs(us: number): void;
  /** The printhead cut the pass or would not run it (too hot, a refused program). */
  refused(): void;
  done(exposure: ScanExposure): void;
}

/** How often the Mega polls `Q` while a pass runs: well inside the Nano's 50 ms silence rule. */
export const PASS_POLL_US = 10_000;

export class ScanPassRun {
  #timers: object[] = [];
  readonly #exposure: ScanExposure;
  readonly #programs: string[][] = [[]];
  #loaded = 0;
  #mark = 0;
  #mask = 0;
  #over = false;

  constructor(private readonly clock: Clock, private readonly nano: NanoModel, scan: ScanPlan, index: number, private readonly hooks: ScanPassHooks) {
    const pass = scan.passes[index];
    this.#exposure = { pass: index, hy: pass.hy, descending: pass.descending, leds: [[], [], [], []] };
    for (const line of programLines(pass.events)) {
      this.#programs[this.#programs.length - 1].push(line);
      if (line.startsWith('K:')) this.#programs.push([]);
    }
    this.#programs.pop();
    nano.onChainSwitch = (mask) => this.#record(mask);
    if (!this.#load(2)) return;
    // A run-up shorter than the G's lead: the head waits for it at rest.
    const start = clock.now + Math.max(0, PROGRAM_START_LEAD_US - scan.accelUs);
    this.#mark = start + scan.accelUs;
    const end = start + passDurationUs(scan, pass);
    this.#timers.push(clock.at(this.#mark - PROGRAM_START_LEAD_US, () => {
      this.nano.command('G\n');
      this.#poll();
    }));
    this.#timers.push(clock.at(start, () => hooks.moveUs(end - start)));
    this.#timers.push(clock.at(end, () => this.#finish()));
  }

  /** Cancels what is left of the pass; the caller puts the LEDs out (R) and stops the head. */
  cancel(): void {
    this.#over = true;
    this.#timers.forEach((e) => this.clock.cancel(e));
    this.#timers = [];
    this.nano.onChainSwitch = null;
  }

  /** Loads up to `n` more programs while the Nano has a free buffer; false (and refused) if one is not armed. */
  #load(n: number): boolean {
    while (n-- > 0 && this.#loaded < this.#programs.length && this.nano.programs.free > 0) {
      let answer: string | null = null;
      for (const line of this.#programs[this.#loaded]) answer = this.nano.command(`${line}\n`);
      this.#loaded++;
      if (answer !== 'K:0\n') {
        this.#stop();
        return false;
      }
    }
    return true;
  }

  /** The Mega's poll while the pass runs: the next program when a buffer is free, and whether the chain was cut. */
  #poll(): void {
    if (this.#over) return;
    const q = parseNanoReply(this.nano.command('Q\n') ?? '');
    if (q?.op !== 'Q' || (q.pass !== PASS.RUNNING && q.pass !== PASS.WHOLE)) return this.#stop();
    if (!this.#load(2)) return;
    this.#timers.push(this.clock.after(PASS_POLL_US, () => this.#poll()));
  }

  /** The head has reached its run-out: the chain has ended whole, or the pass is cut. */
  #finish(): void {
    if (this.#over) return;
    const q = parseNanoReply(this.nano.command('Q\n') ?? '');
    if (q?.op !== 'Q' || q.pass !== PASS.WHOLE) return this.#stop();
    this.cancel();
    this.hooks.done(this.#exposure);
  }

  #stop(): void {
    this.cancel();
    this.hooks.refused();
  }

  #record(mask: number): void {
    const at = this.clock.now - this.#mark;
    for (let k = 0; k < 4; k++) {
      const was = (this.#mask >> k) & 1, is = (mask >> k) & 1;
      if (!was && is) this.#exposure.leds[k].push([at, at]);
      if (was && !is) this.#exposure.leds[k][this.#exposure.leds[k].length - 1][1] = at;
    }
    this.#mask = mask;
  }
}
