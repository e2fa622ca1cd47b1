// The grid as the screen draws it: 256 × 256-cell tiles at levels of detail, each level half the
// cells of the one below. A coarser cell holds the darkest of the four below it, so a one-cell
// trace stays visible when the whole 4096² bed is on screen. Tiles are remade only when an edit
// marks them dirty, so panning redraws nothing but the screen.

import type { DoseGrid } from '../grid/grid';

export const TILE = 256;

/** Dose → colour on screen (ABGR for a little-endian Uint32Array over RGBA): bed white to UV violet. */
export function doseColours(): Uint32Array {
  const lut = new Uint32Array(256);
  for (let d = 0; d < 256; d++) {
    const t = d / 255;
    const r = Math.round(250 - t * (250 - 74)), g = Math.round(250 - t * (250 - 20)), b = Math.round(250 - t * (250 - 140));
    lut[d] = (255 << 24) | (b << 16) | (g << 8) | r;
  }
  return lut;
}

export class LevelGrid {
  readonly cols: number;
  readonly rows: number;
  readonly cells: Uint8Array;
  constructor(cols: number, rows: number) {
    this.cols = cols;
    this.rows = rows;
    this.cells = new Uint8Array(cols * rows);
  }
}

/** An edited box still to be carried to the coarser levels: its level-0 cells, the level being made and its next row there. */
interface Remake {
  x0: number;
  y0: number;
  x1: number;
  y1: number;
  level: number;
  row: number;
}

/** A coarser level's rows made between two looks at the clock: about 256 K cells of the level below. */
const BAND_CELLS = 1 << 18;

export class TileCache<T> {
  readonly #levels: (DoseGrid | LevelGrid)[];
  /**
   * The boxes edited since the coarser levels were last made, oldest first. They are made in the
   * frames that draw, a few milliseconds of each (`catchUp`), not in the edit's own task: a whole-bed
   * fill's level 1 alone (4 M cells) took 60 ms of one frame on a busy machine (issue 40). Past 64
   * boxes, those not yet begun are merged into one.
   */
  #remakes: Remake[] = [];
  #tiles = new Map<string, { tile: T; dirty: boolean }>();
  readonly #lut = doseColours();
  #everPainted: boolean;

  constructor(
    readonly grid: DoseGrid,
    private readonly makeTile: (w: number, h: number) => T,
    private readonly paint: (tile: T, pixels: Uint32Array, w: number, h: number) => void,
    /** Whether the grid may hold doses; false for a blank one (the editor knows: its hasInk). */
    painted = true,
  ) {
    this.#levels = [grid];
    let cols = grid.cols, rows = grid.rows;
    while (cols > TILE || rows > TILE) {
      cols = Math.ceil(cols / 2);
      rows = Math.ceil(rows / 2);
      this.#levels.push(new LevelGrid(cols, rows));
    }
    // The coarser levels start blank: a blank grid (the page's first load) has nothing to make them from,
    // and reading its 16 M cells to find that out was 58 ms of the page's load on a busy machine (issue 40).
    this.#everPainted = painted;
    if (painted) this.refresh(0, 0, grid.cols - 1, grid.rows - 1);
  }

  /** Level 0 is the grid itself; level k has ceil(cols / 2^k) cells across, every one made up to date when read. */
  get levels(): readonly (DoseGrid | LevelGrid)[] {
    this.catchUp(Infinity);
    return this.#levels;
  }

  /**
   * No cell has had a dose since the cache was made for a blank grid: every tile would be the bed's
   * own colour, which the frame draws anyway (the first frame painted 16 blank tiles on the page's load).
   */
  get blank(): boolean {
    return !this.#everPainted;
  }

  /** The levels as they are now, parts of the coarser ones perhaps not yet remade after an edit (see `catchUp`). */
  get levelsSoFar(): readonly (DoseGrid | LevelGrid)[] {
    return this.#levels;
  }

  /**
   * Carries the edits to the coarser levels until `until` (a `performance.now()` time), a band of
   * rows at a time, each level's tiles marked to be repainted as its rows are made. True when no
   * edit is left to carry: otherwise the caller draws again in the next frame.
   */
  catchUp(until: number): boolean {
    const queue = this.#remakes;
    while (queue.length) {
      const r = queue[0];
      if (r.level === 0) {
        this.#dirty(0, r.x0, r.y0, r.x1, r.y1);
        r.level = 1;
        r.row = r.y0 >> 1;
      }
      while (r.level < this.#levels.length) {
        const f = r.level - 1, x0 = r.x0 >> f, x1 = r.x1 >> f, y1 = Math.min(r.y1 >> r.level, this.#levels[r.level].rows - 1);
        if (r.row > y1) {
          r.level++;
          r.row = r.y0 >> r.level;
          continue;
        }
        const band = Math.max(1, Math.floor(BAND_CELLS / (2 * (x1 - x0 + 2))));
        const last = Math.min(y1, r.row + band - 1);
        this.#downsample(r.level, x0, 2 * r.row, x1, 2 * last + 1);
        this.#dirty(r.level, x0 >> 1, r.row, x1 >> 1, last);
        r.row = last + 1;
        if (performance.now() >= until) {
          if (r.row > y1 && r.level === this.#levels.length - 1) queue.shift();
          return queue.length === 0;
        }
      }
      queue.shift();
    }
    return true;
  }

  /** After an edit of the cells in [x0, x1] × [y0, y1]: the coarser levels and the tiles over it, remade when next drawn or read. */
  refresh(x0: number, y0: number, x1: number, y1: number): void {
    x0 = Math.max(0, x0), y0 = Math.max(0, y0);
    x1 = Math.min(this.grid.cols - 1, x1), y1 = Math.min(this.grid.rows - 1, y1);
    if (x0 > x1 || y0 > y1) return;
    this.#everPainted = true;
    const queue = this.#remakes;
    queue.push({ x0, y0, x1, y1, level: 0, row: 0 });
    if (queue.length > 64) {
      const begun = queue[0].level > 0 ? 1 : 0;
      const merged = queue.slice(begun).reduce((a, b) => ({ x0: Math.min(a.x0, b.x0), y0: Math.min(a.y0, b.y0), x1: Math.max(a.x1, b.x1), y1: Math.max(a.y1, b.y1), level: 0, row: 0 }));
      this.#remakes = [...queue.slice(0, begun), merged];
    }
  }

  /** Marks level k's tiles over its cells [x0, x1] × [y0, y1] to be repainted. */
  #dirty(k: number, x0: number, y0: number, x1: number, y1: number): void {
    for (let ty = Math.floor(y0 / TILE); ty <= Math.floor(y1 / TILE); ty++)
      for (let tx = Math.floor(x0 / TILE); tx <= Math.floor(x1 / TILE); tx++) {
        const t = this.#tiles.get(`${k}/${tx}/${ty}`);
        if (t) t.dirty = true;
      }
  }

  /**
   * Level k's cells over level k-1's box [x0, x1] × [y0, y1]: each the darkest of the four below it. A
   * row at a time with plain compares, a missing second row or column read as the first: with a
   * bounds check and Math.max per cell, a whole 4000² bed took 100 ms of the page's thread at load and
   * after a whole-bed fill on a busy machine (issue 40's long tasks).
   */
  #downsample(k: number, x0: number, y0: number, x1: number, y1: number): void {
    const src = this.#levels[k - 1], dst = this.#levels[k];
    const s = src.cells, d = dst.cells, sc = src.cols;
    const xa = x0 >> 1, xb = Math.min(x1 >> 1, dst.cols - 1), ya = y0 >> 1, yb = Math.min(y1 >> 1, dst.rows - 1);
    const pairs = Math.min(xb, (sc >> 1) - 1); // the last column with two cells below it
    for (let y = ya; y <= yb; y++) {
      const a = 2 * y * sc, b = 2 * y + 1 < src.rows ? a + sc : a, o = y * dst.cols;
      for (let x = xa; x <= pairs; x++) {
        const i = 2 * x;
        let m = s[a + i], v = s[a + i + 1];
        if (v > m) m = v;
        v = s[b + i];
        if (v > m) m = v;
        v = s[b + i + 1];
        if (v > m) m = v;
        d[o + x] = m;
      }
      if (xb > pairs) d[o + xb] = Math.max(s[a + 2 * xb], s[b + 2 * xb]); // an odd last column
    }
  }

  /** The level to draw at `scale` screen pixels per cell: the coarsest whose cells are still ≥ 1 pixel. */
  levelFor(scale: number): number {
    let k = 0;
    while (k + 1 < this.#levels.length && scale * Math.pow(2, k + 1) <= 1) k++;
    return k;
  }

  /** Tile (tx, ty) of level k, made or remade if needed, from the level as it is so far (`catchUp` first). */
  tile(k: number, tx: number, ty: number): T {
    const key = `${k}/${tx}/${ty}`;
    const level = this.#levels[k];
    const w = Math.min(TILE, level.cols - tx * TILE), h = Math.min(TILE, level.rows - ty * TILE);
    let t = this.#tiles.get(key);
    if (!t) {
      t = { tile: this.makeTile(w, h), dirty: true };
      this.#tiles.set(key, t);
    }
    if (t.dirty) {
      const pixels = new Uint32Array(w * h);
      for (let y = 0; y < h; y++) {
        const row = (ty * TILE + y) * level.cols + tx * TILE;
        for (let x = 0; x < w; x++) pixels[y * w + x] = this.#lut[level.cells[row + x]];
      }
      this.paint(t.tile, pixels, w, h);
      t.dirty = false;
    }
    return t.tile;
  }

  /** How many tiles are held (for the memory figure). */
  get size(): number {
    return this.#tiles.size;
  }
}
