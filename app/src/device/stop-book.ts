// The stops a dose ledger holds, and the order their changes came in since it was last cleared: kept
// by the page's ledger (dose-ledger.ts) as the Mega's lines come, and by the work worker's mirror of
// it (job/dose-batch.ts) as the page's batches come. A view asks for the changes since the line it
// last counted, and counts every stop again when the clears differ.

export class StopBook<S> {
  readonly stops = new Map<number, S>();
  /** The stop of each change since the last clear, in order. */
  readonly #log: number[] = [];
  #clears: number;

  /** `clears`: the count a fresh book starts from (a mirror that has heard nothing: −1). */
  constructor(clears = 0) {
    this.#clears = clears;
  }

  get clears(): number {
    return this.#clears;
  }

  stop(n: number): S | undefined {
    return this.stops.get(n);
  }

  /** Stop `n` changed (it is set, replaced or deleted in `stops`). */
  changed(n: number): void {
    this.#log.push(n);
  }

  /** The stops of the changes from change `from` on (0 the first since the last clear), how many changes there are now, and the clears so far. */
  since(from: number): { stops: number[]; lines: number; clears: number } {
    return { stops: this.#log.slice(from), lines: this.#log.length, clears: this.#clears };
  }

  /** Empties the book; its clears become `clears` (one more by default). */
  clear(clears = this.#clears + 1): void {
    this.stops.clear();
    this.#log.length = 0;
    this.#clears = clears;
  }
}
