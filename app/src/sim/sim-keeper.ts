// Decides what of the simulated printer to write to the browser's store, and when: the card when
// what it durably holds changes (a job written, a checkpoint synced, a file removed), the machine
// record (EEPROM, start count, a running job) when it changes. Both go in one write, so a checkpoint
// is never kept without the job file it names. One write at a time: what changes meanwhile goes in
// the next.

import type { Keeping } from './sim-messages';
import type { SimPrinter } from './sim-printer';
import { machineRecord, type RunningJob } from './sim-snapshot';

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
    const m = this.printer.module;
    const entries: StoreEntries = [];
    const cardRevision = m.cardRevision;
    const saved = { files: cardRevision !== this.#cardRevision ? m.card() : [], eeprom: m.eeprom(), boots: m.starts };
    if (cardRevision !== this.#cardRevision) entries.push(['card', saved.files]);
    const job = this.#off ? null : m.cardJob();
    // A running job's record goes again with each checkpoint the card takes: the time it keeps is
    // the checkpoint's, which a reload runs the job on from.
    const machineKey = JSON.stringify([m.eepromWrites, saved.boots, job, job ? cardRevision : 0]);
    if (machineKey !== this.#machineKey) {
      // The time and the speed go with a running job: a reload runs it on from its checkpoint.
      const running: RunningJob | null = job && { atMs: this.wallMs(), speed: this.speed(), paced: job.paced };
      entries.push(['machine', machineRecord(saved, running)]);
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
