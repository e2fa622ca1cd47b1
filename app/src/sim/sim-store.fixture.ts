// Test-only: the browser's store as the simulated printer's keeper sees it, and a small job to keep.

import { GEOMETRIES, randomJob } from '../planner/test-jobs';
import type { StoreEntries } from './sim-keeper';
import { readKept } from './sim-snapshot';

/** Structured clones, each write whole, as IndexedDB keeps them; `hold` delays writes, `fail` fails them. */
export class FakeStore {
  readonly values = new Map<IDBValidKey, unknown>();
  /** The keys of each write, in order. */
  readonly writes: string[][] = [];
  fail = false;
  hold: Promise<void> | null = null;

  write = async (entries: StoreEntries): Promise<void> => {
    await this.hold;
    if (this.fail) throw new Error('QuotaExceededError');
    this.writes.push(entries.map(([k]) => String(k)));
    for (const [k, v] of entries) this.values.set(k, structuredClone(v));
  };

  kept() {
    return readKept(this.values.get('card'), this.values.get('machine'));
  }
}

export function smallJob(seed: number) {
  const job = randomJob(seed, GEOMETRIES.adjacent, 'serpentine', [24, 12], 0.4);
  job.originUm = { x: 20000, y: 30000 };
  job.pitchUm = { x: 50, y: 50 };
  job.dose = { map: 'linear', fullUs: 4000 };
  return job;
}
