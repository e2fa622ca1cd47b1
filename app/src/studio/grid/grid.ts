// A machine-sized grid of doses: one byte a cell (0 = no light, 255 = the full dose), row 0 first.

export const MAX_SIDE = 4096;

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
  bounds(): { x0: number; y0: number; x1: number; y1: number } | null {
    let x0 = this.cols, y0 = this.rows, x1 = -1, y1 = -1;
    // Four cells a word where rows allow it: a whole bed's empty rows are skipped four times as fast,
    // which keeps composing a job within the page's 50 ms (issue 29).
    const words = this.cols % 4 === 0 && this.cells.byteOffset % 4 === 0 ? new Uint32Array(this.cells.buffer, this.cells.byteOffset, this.cells.length >> 2) : null;
    for (let y = 0; y < this.rows; y++) {
      const row = this.cells.subarray(y * this.cols, (y + 1) * this.cols);
      let from = 0;
      if (words) {
        const w0 = (y * this.cols) >> 2, n = this.cols >> 2;
        let w = 0;
        while (w < n && !words[w0 + w]) w++;
        if (w === n) continue;
        from = w * 4;
      }
      let first = -1;
      for (let x = from; x < row.length; x++) if (row[x]) { first = x; break; }
      if (first < 0) continue;
      let last = row.length - 1;
      while (!row[last]) last--;
      x0 = Math.min(x0, first);
      x1 = Math.max(x1, last);
      y0 = Math.min(y0, y);
      y1 = y;
    }
    return x1 < 0 ? null : { x0, y0, x1, y1 };
  }
}
