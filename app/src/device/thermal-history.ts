// The last 20 minutes of the six temperatures, a ring of columns that uPlot can draw as they are.

export const HISTORY_S = 20 * 60;

export class ThermalHistory {
  readonly capacity: number;
  #t: Float64Array;
  #c: Float64Array[];
  #lit: Uint8Array;
  #next = 0;
  #size = 0;
  /** Bumped on every sample, so views can follow. */
  revision = 0;

  /** Room for 20 minutes of the once-a-second report, and some to spare. */
  constructor(capacity = HISTORY_S + 60) {
    this.capacity = capacity;
    this.#t = new Float64Array(capacity);
    this.#c = Array.from({ length: 6 }, () => new Float64Array(capacity));
    this.#lit = new Uint8Array(capacity);
  }

  get size(): number {
    return this.#size;
  }

  /** One report: seconds since the epoch, °C of each sensor, whether a job was exposing. */
  add(tS: number, celsius: number[], exposing: boolean): void {
    if (this.#size && tS <= this.#t[(this.#next + this.capacity - 1) % this.capacity]) return; // out of order
    this.#t[this.#next] = tS;
    for (let i = 0; i < 6; i++) this.#c[i][this.#next] = celsius[i] ?? NaN;
    this.#lit[this.#next] = exposing ? 1 : 0;
    this.#next = (this.#next + 1) % this.capacity;
    this.#size = Math.min(this.#size + 1, this.capacity);
    this.revision++;
  }

  clear(): void {
    this.#next = this.#size = 0;
    this.revision++;
  }

  /** Oldest first: [times, T0 … T5], the samples of the last `spanS` seconds. */
  columns(spanS = HISTORY_S): [number[], ...number[][]] {
    const out: [number[], ...number[][]] = [[], [], [], [], [], [], []];
    for (const i of this.#within(spanS)) {
      out[0].push(this.#t[i]);
      for (let c = 0; c < 6; c++) out[c + 1].push(this.#c[c][i]);
    }
    return out;
  }

  /** The samples of the last `spanS` seconds, for the rate watch. */
  recent(spanS: number): { tS: number; celsius: number[]; exposing: boolean }[] {
    return this.#within(spanS).map((i) => ({ tS: this.#t[i], celsius: this.#c.map((c) => c[i]), exposing: this.#lit[i] === 1 }));
  }

  /** The ring's slots of the samples no older than `spanS` before the newest, oldest first. */
  #within(spanS: number): number[] {
    const start = (this.#next - this.#size + this.capacity) % this.capacity;
    const newest = this.#size ? this.#t[(this.#next + this.capacity - 1) % this.capacity] : 0;
    const out: number[] = [];
    for (let k = 0; k < this.#size; k++) {
      const i = (start + k) % this.capacity;
      if (this.#t[i] >= newest - spanS) out.push(i);
    }
    return out;
  }
}
