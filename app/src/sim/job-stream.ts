// Stream mode on the simulated Mega (protocol/mega.md M828): a job's records are checked as they arrive,
// held in a bounded buffer and exposed as soon as no later row can change the stops that read them.
// A record that does not fit waits for its `ok`, which holds back the host through its window.

import { planAnyJob } from '../planner/job-plan';
import type { Machine } from '../planner/time-model';
import type { JobHeader } from '../protocol/job-types';
import { JobVerifier, type JobError } from '../protocol/job-verify';
import type { JobRunner } from './job-runner';

/** Cells of arrived rows the Mega holds until every stop that reads them has been exposed. */
export const STREAM_BUFFER_CELLS = 4096;

/** A record's error (E23-E25), or E28 when the buffer cannot hold the rows the next stops (or pass) need. */
export type StreamError = Omit<JobError, 'code'> & { code: JobError['code'] | 28 };

export class JobStream {
  readonly verifier: JobVerifier;
  /** The first error: a bad record, a bad hash or an overflow. Nothing after it is exposed. */
  error: StreamError | null = null;
  #header: JobHeader | null = null;
  #cells: Uint8Array[] = [];
  #rowCells = new Uint32Array(0);
  /** Rows below this have all arrived. */
  #known = 0;
  #planned = -1;
  #held = 0;
  #heldFrom = 0;
  #dyMin = 0;
  #waiting: (() => void) | null = null;

  constructor(
    private readonly job: JobRunner,
    private readonly machine: Machine,
    private readonly report: (e: StreamError) => void,
  ) {
    this.verifier = new JobVerifier((s) => {
      this.#cells[s.row].set(s.cells, s.col);
      this.#rowCells[s.row] += s.cells.length;
      this.#held += s.cells.length;
      this.#known = Math.max(this.#known, s.row);
    });
  }

  /** A record is waiting for room in the buffer: its `ok` comes when exposure frees some. */
  get holding(): boolean {
    return this.#waiting !== null;
  }

  get heldCells(): number {
    return this.#held;
  }

  /** One record; `done` sends its `ok`, later if the buffer is full. */
  push(record: string, done: () => void): void {
    if (this.error || !this.live) return done(); // after a failure or an abort the rest is only read
    const err = this.verifier.push(record);
    if (err) {
      this.#fail(err);
      return done();
    }
    const h = this.verifier.header;
    if (h && !this.#header) {
      this.#header = h;
      this.#cells = Array.from({ length: h.rows }, () => new Uint8Array(h.cols));
      this.#rowCells = new Uint32Array(h.rows);
      this.#dyMin = Math.min(...h.offsets.map((o) => o[1]));
    }
    if (this.verifier.complete) this.#known = h!.rows;
    this.#waiting = done;
    this.progress();
  }

  /** After a stop is exposed, a record arrives or the job changes state: plan on, free rows, answer the waiting record. */
  progress(): void {
    if (!this.live) return this.#answer();
    const h = this.#header;
    if (h && this.#known > this.#planned && (this.job.starved || this.#held > STREAM_BUFFER_CELLS || this.#known === h.rows)) {
      this.#planned = this.#known;
      // A scan job's passes too (the Mega's ScanPlanner::setKnownRows): each once all its rows are here.
      const { plan, scan } = planAnyJob({ header: h, cells: this.#cells, knownRows: this.#known }, this.machine);
      this.job.extend(h, plan, this.#known === h.rows, scan);
    }
    if (this.#held > STREAM_BUFFER_CELLS) this.#release();
    if (this.#held <= STREAM_BUFFER_CELLS) return this.#answer();
    if (this.job.starved) {
      // The rows the next stops need do not fit: the job cannot go on. What is exposed stays exposed.
      this.#fail({ code: 28, line: 0, message: `the next stops need more than ${STREAM_BUFFER_CELLS} buffered cells` });
      this.#answer();
    }
  }

  /** M29: the stream's verdict. */
  finish(): StreamError | null {
    this.error ??= this.verifier.finish();
    if (this.error) this.job.abort();
    return this.error;
  }

  get live(): boolean {
    return this.job.streaming && (this.job.state === 'running' || this.job.state === 'paused');
  }

  #answer(): void {
    const done = this.#waiting;
    this.#waiting = null;
    done?.();
  }

  #fail(err: StreamError): void {
    this.error = err;
    this.report(err);
    this.job.abort(); // LEDs off; cells already exposed stay exposed
  }

  /** Frees the rows below the lowest one any stop still to run, or any pass still to come, can read. */
  #release(): void {
    const p = this.job.plan;
    if (!p) return;
    let lowest = Infinity;
    for (let i = this.job.done; i < p.count; i++) lowest = Math.min(lowest, p.hy[i]);
    if (lowest === Infinity) {
      // Every planned stop has run: the next pass opens above the last one planned.
      lowest = -Infinity;
      for (let i = 0; i < p.count; i++) lowest = Math.max(lowest, p.hy[i] + 1);
      if (lowest === -Infinity) return;
    }
    const upTo = Math.min(lowest + this.#dyMin, this.#known);
    for (; this.#heldFrom < upTo; this.#heldFrom++) this.#held -= this.#rowCells[this.#heldFrom];
  }
}
