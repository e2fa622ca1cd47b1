// A machine-sized grid of doses: one byte a cell (0 = no light, 255 = the full dose), row 0 first.

export const MAX_SIDE = 4096;

/** A box of cells, both corners included. */
export interface Box {
  x0: number;
  y0: number;
  x1: number;
  y1: number;
}

export class DoseGrid {
  readonly cells: Uint8Array;

  constructor(
    readonly cols: number,
    readonly rows: number,
    cells?: Uint8Array,
  ) {
    if (!Number.isInteger(cols) || !Number.isInteger(rows) || cols < 1 || rows < 1 || cols > MAX_SIDE || rows > MAX_SIDE) {
      throw new RangeError(`a grid is 1-${MAX_SIDE} cells a side, not ${cols} × ${rows}`);
    }
    this.cells = cells ?? new Uint8Array(cols * rows);
    if (this.cells.length !== cols * rows) throw new RangeError('cells do not match the grid size');
  }

  /** The grid a machine exposes: its bed over its cell pitch, capped at 4096 a side. */
  static forBed(bedMm: { x: number; y: number }, pitchUm: { x: number; y: number }): DoseGrid {
    const { cols, rows } = DoseGrid.sizeForBed(bedMm, pitchUm);
    return new DoseGrid(cols, rows);
  }

  /** The size of that grid, without making it. */
  static sizeForBed(bedMm: { x: number; y: number }, pitchUm: { x: number; y: number }): { cols: number; rows: number } {
    return {
      cols: Math.min(MAX_SIDE, Math.max(1, Math.floor((bedMm.x * 1000) / pitchUm.x))),
      rows: Math.min(MAX_SIDE, Math.max(1, Math.floor((bedMm.y * 1000) / pitchUm.y))),
    };
  }

  inside(x: number, y: number): boolean {
    return x >= 0 && y >= 0 && x < this.cols && y < this.rows;
  }

  get(x: number, y: number): number {
    return this.cells[y * this.cols + x];
  }

  /** Rows as a job's gridData, without copying. */
  rowsView(): Uint8Array[] {
    return Array.from({ length: this.rows }, (_, y) => this.cells.subarray(y * this.cols, (y + 1) * this.cols));
  }

  /** The smallest box holding every cell with a dose, or null for an empty grid. */
  bounds(): Box | null {
    const box = { x0: this.cols, y0: this.rows, x1: -1, y1: -1 };
    this.#boundsOfRows(0, this.rows - 1, box);
    return box.x1 < 0 ? null : box;
  }

  /**
   * The same, a band of rows per task (`pause` between): a whole bed's bounds in one go were 43–57 ms
   * of the page's thread before a dry run on a busy machine (issue 40).
   */
  async boundsSoon(pause: () => Promise<unknown>, bandCells = 1 << 22): Promise<Box | null> {
    const box = { x0: this.cols, y0: this.rows, x1: -1, y1: -1 };
    const band = Math.max(1, Math.floor(bandCells / this.cols));
    for (let y = 0; y < this.rows; y += band) {
      if (y > 0) await pause();
      this.#boundsOfRows(y, Math.min(this.rows, y + band) - 1, box);
    }
    return box.x1 < 0 ? null : box;
  }

  /** Widens `box` to hold every cell with a dose in rows `from`..`to`. */
  #boundsOfRows(from: number, to: number, box: Box): void {
    // Four cells a word where rows allow it: a whole bed's empty rows are skipped four times as fast,
    // which keeps composing a job within the page's 50 ms (issue 29).
    const words = this.cols % 4 === 0 && this.cells.byteOffset % 4 === 0 ? new Uint32Array(this.cells.buffer, this.cells.byteOffset, this.cells.length >> 2) : null;
    for (let y = from; y <= to; y++) {
      const row = this.cells.subarray(y * this.cols, (y + 1) * this.cols);
      let start = 0;
      if (words) {
        const w0 = (y * this.cols) >> 2, n = this.cols >> 2;
        let w = 0;
        while (w < n && !words[w0 + w]) w++;
        if (w === n) continue;
        start = w * 4;
      }
      let first = -1;
      for (let x = start; x < row.length; x++) if (row[x]) { first = x; break; }
      if (first < 0) continue;
      let last = row.length - 1;
      while (!row[last]) last--;
      box.x0 = Math.min(box.x0, first);
      box.x1 = Math.max(box.x1, last);
      box.y0 = Math.min(box.y0, y);
      box.y1 = y;
    }
  }
}
