// Decides what of the simulated printer to write to the browser's store, and when: the card when a
// file is written or deleted, the machine record (checkpoint, EEPROM, start count, a running job)
// when it changes, which is at the pace the Mega writes checkpoints, after each stop. Both go in one
// write, so a checkpoint is never kept without the job file it names. One write at a time: what
// changes meanwhile goes in the next.

import type { Keeping } from './sim-messages';
import type { SimPrinter } from './sim-printer';
import { jobRunning, machineRecord } from './sim-snapshot';

export type StoreEntries = [IDBValidKey, unknown][];

export class SimKeeper {
  #cardRevision = -1;
  #machineKey = '';
  #writing: Promise<void> | null = null;
  #off = false;
  #failed = false;

  /**
   * `write` puts the entries in the store in one transaction; `speed` is the printer's speed now;
   * `onFailure` hears once if a write fails, after which nothing more is written.
   */
  constructor(
    private readonly printer: SimPrinter,
    private readonly write: (entries: StoreEntries) => Promise<void>,
    private readonly speed: () => number,
    private readonly onFailure: (error: unknown) => void = () => {},
    private readonly wallMs: () => number = () => Date.now(),
  ) {}

  /** Writes what changed since the last write, unless a write is under way (the next call takes it). */
  keep(): Promise<void> | null {
    if (this.#writing || this.#failed) return null;
    const p = this.printer;
    const entries: StoreEntries = [];
    const cardRevision = p.sd.files.revision;
    if (cardRevision !== this.#cardRevision) entries.push(['card', [...p.sd.files]]);
    const running = !this.#off && jobRunning(p);
    const machineKey = JSON.stringify([p.sd.checkpoint, p.mega.eeprom, p.boots, running]);
    if (machineKey !== this.#machineKey) {
      // The head's place and the time go with each checkpoint: a reload runs the job on from there.
      entries.push(['machine', machineRecord(p, running ? { pos: p.mega.motion.now(), atMs: this.wallMs(), speed: this.speed() } : null)]);
    }
    if (!entries.length) return null;
    this.#writing = this.write(entries).then(
      () => {
        this.#cardRevision = cardRevision;
        this.#machineKey = machineKey;
      },
      (e) => {
        this.#failed = true;
        this.onFailure(e);
      },
    ).finally(() => (this.#writing = null));
    return this.#writing;
  }

  /**
   * The printer is switched off (the app connects to a real one): it will not run on. Resolves once
   * that is written, after a write under way.
   */
  async switchOff(): Promise<void> {
    this.#off = true;
    await this.#writing;
    await this.keep();
  }
}

/** What the page says about how the printer is kept, when it is not simply kept; `damage` is sim-snapshot's note. */
export function keepingNote(keeping: Keeping, damage: string | null): string | null {
  if (keeping === 'another tab') return 'Another tab has the simulated printer: this tab has a second one, with an empty card, that a reload does not keep.';
  if (keeping === 'unavailable') return 'This browser could not open a store for the simulated printer (IndexedDB is off or damaged): it starts clean on every reload.';
  if (keeping === 'failed') return 'The simulated printer could no longer be kept in this browser (a write failed): a reload may find an older card.';
  return damage;
}
