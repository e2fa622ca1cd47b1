// What the printhead delivered to a job, stop by stop and program by program, folded from the Mega's
// DOSE: lines (protocol/mega.md "Dose reports"): each stop's light counted once, its cut light kept
// apart, and the stops a fault or a resume lit twice.

import type { DoseReport } from '../protocol/dialect-reply';
import { StopBook } from './stop-book';

/** One stop's light: a stop's F is program 0; a pass on the move has one entry a program. */
export interface StopDose {
  /** Each program's on-times per LED in µs, by its place in the pass's chain. */
  programs: Map<number, number[]>;
  /** What a cut F was to give (thermally compensated); a whole F gives what was sent. */
  planUs?: number[];
  /** Light a fault or a restart cut short, before the stop was exposed again. */
  cutUs: number[][];
  /** Its cells got light twice: a cut exposure, then the stop's exposure again. */
  twice: boolean;
  /** Lines folded in: a view that counted the stop before sees whether it changed. */
  lines: number;
}

export interface DoseSummary {
  /** Stops with light counted. */
  stops: number;
  /** Stops that a cut or a resume lit twice, in order. */
  twice: number[];
  /** Stops whose light was cut and not (yet) given again. */
  cutOnly: number[];
}

const ENDED = new Set(['idle', 'ready', 'done', 'aborted', 'failed']);

export class DoseLedger {
  /** Each stop's light, and the stop of each line folded in since the last clear: a view counts again only those. */
  readonly #book = new StopBook<StopDose>();
  #file: string | undefined;
  #ended = true;

  /**
   * Follows the job reports: a job that starts (from its first stop, after one ended) or another
   * job's file begins a new ledger; a job that continues or resumes keeps what was reported.
   */
  job(state: string, file: string | undefined, stop: number | undefined): void {
    const live = state === 'running' || state === 'paused';
    if (live && ((file !== undefined && file !== this.#file) || (this.#ended && stop === 0))) {
      this.clear();
      this.#file = file;
    }
    if (live) this.#ended = false;
    else if (ENDED.has(state)) this.#ended = true;
  }

  /** The job the ledger is about. */
  get file(): string | undefined {
    return this.#file;
  }

  /** Folds one line's report in. A second report of a stop's program replaces the first. */
  add(r: DoseReport): void {
    let s = this.#book.stop(r.stop);
    if (!s) {
      s = { programs: new Map(), cutUs: [], twice: false, lines: 0 };
      this.#book.stops.set(r.stop, s);
    }
    s.lines++;
    this.#book.changed(r.stop);
    if (r.again) s.twice = true;
    if (r.planUs) s.planUs = [...r.planUs];
    if (r.cut) {
      s.cutUs.push([...r.onUs]);
      if (s.programs.size) s.twice = true;  // a stop cut after light counted (a resume found it)
      return;
    }
    s.programs.set(r.program, [...r.onUs]);
    if (s.cutUs.length) s.twice = true;
  }

  stop(n: number): StopDose | undefined {
    return this.#book.stop(n);
  }

  /** The light counted for a stop, per LED in µs: its programs summed; undefined if none reported. */
  delivered(n: number): number[] | undefined {
    const s = this.#book.stop(n);
    if (!s || !s.programs.size) return undefined;
    const sum = [0, 0, 0, 0];
    for (const on of s.programs.values()) on.forEach((v, k) => (sum[k] += v));
    return sum;
  }

  summary(): DoseSummary {
    const twice: number[] = [];
    const cutOnly: number[] = [];
    let stops = 0;
    for (const [n, s] of [...this.#book.stops].sort((a, b) => a[0] - b[0])) {
      if (s.programs.size) stops++;
      else if (s.cutUs.length) cutOnly.push(n);
      if (s.twice) twice.push(n);
    }
    return { stops, twice, cutOnly };
  }

  /** The stops of the lines folded in from line `from` on (0 the first since the last clear), how many lines there are now, and the clears so far. */
  since(from: number): { stops: number[]; lines: number; clears: number } {
    return this.#book.since(from);
  }

  clear(): void {
    this.#book.clear();
  }
}
