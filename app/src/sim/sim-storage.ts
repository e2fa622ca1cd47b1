// The browser's side of keeping the simulated printer (its worker calls this): IndexedDB through
// idb-keyval, and a Web Lock so that one tab at a time keeps it. A second tab gets a printer of its own.

import { createStore, getMany, setMany, type UseStore } from 'idb-keyval';
import { readKept, type Kept } from './sim-snapshot';
import type { StoreEntries } from './sim-keeper';

const LOCK = 'uv-exposure-simulated-printer';

let db: UseStore | null = null;
const store = () => (db ??= createStore('uv-exposure-sim', 'printer'));

/**
 * Holds the store for as long as this worker lives. False if another tab's printer holds it: after
 * `waitMs`, which lets a printer switched off just now (its worker closing) let go first.
 */
export function claimStore(waitMs = 1000): Promise<boolean> {
  const locks = typeof navigator !== 'undefined' ? navigator.locks : undefined;
  if (!locks) return Promise.resolve(true);
  return new Promise((resolve) => {
    locks
      .request(LOCK, { signal: AbortSignal.timeout(waitMs) }, () => {
        resolve(true);
        return new Promise<void>(() => {}); // held until the worker ends
      })
      .catch(() => resolve(false));
  });
}

/** What the store holds, read back with care (sim-snapshot.ts); throws if there is no IndexedDB. */
export async function loadKept(): Promise<Kept> {
  const [card, machine] = await getMany(['card', 'machine'], store());
  return readKept(card, machine);
}

export function writeKept(entries: StoreEntries): Promise<void> {
  return setMany(entries, store());
}
