// The page's dose ledger (device/dose-ledger.ts) carried to the work worker a batch at a time: the
// page sends the stops whose lines came since the worker last heard, each as the ledger holds it now;
// the worker's mirror takes them, and answers the delivered-dose map's questions as the ledger would.

import type { DoseLedger, StopDose } from '../device/dose-ledger';
import { StopBook } from '../device/stop-book';
import type { DoseLedgerView } from './dose-map';

/** The stops that changed since the last batch; a new `clears` starts the ledger again. */
export interface DoseBatch {
  clears: number;
  stops: [number, StopDose | null][];
}

/** What the worker has heard of the ledger: its lines, and its clears (−1: nothing yet). */
export interface Heard {
  lines: number;
  clears: number;
}

export const NOTHING_HEARD: Heard = { lines: 0, clears: -1 };

/** The batch that brings a worker that heard `heard` up to the ledger, and what it has heard then. */
export function batchSince(ledger: Pick<DoseLedger, 'since' | 'stop'>, heard: Heard): { batch: DoseBatch; heard: Heard } {
  let since = ledger.since(heard.lines);
  if (since.clears !== heard.clears) since = ledger.since(0); // cleared since (another job): all of it
  const stops = [...new Set(since.stops)].map((n): [number, StopDose | null] => [n, ledger.stop(n) ?? null]);
  return { batch: { clears: since.clears, stops }, heard: { lines: since.lines, clears: since.clears } };
}

/** The ledger as the worker has heard it: each stop as last sent, and the order its changes came in. */
export class LedgerMirror implements DoseLedgerView {
  readonly #book = new StopBook<StopDose>(-1);

  apply(batch: DoseBatch): void {
    if (batch.clears !== this.#book.clears) this.#book.clear(batch.clears);
    for (const [n, s] of batch.stops) {
      if (s) this.#book.stops.set(n, s);
      else this.#book.stops.delete(n);
      this.#book.changed(n);
    }
  }

  stop(n: number): StopDose | undefined {
    return this.#book.stop(n);
  }

  since(from: number): { stops: number[]; lines: number; clears: number } {
    return this.#book.since(from);
  }
}
