// Turns the chosen layers of a board into a grid of cells: each cell's covered fraction, and whether it reaches the threshold.
//
// Coverage is exact across each scan line (the intervals shapes cover are computed in closed form) and
// sampled down the cell on LINES_PER_CELL lines at the centres of equal strips. Straight edges that are not
// horizontal come out exact; a horizontal edge or a corner inside a cell errs by at most 1/(2·LINES_PER_CELL)
// of the cell (3.3 %), and arcs are chords within 0.1 µm. With an odd count the middle line runs through the
// cell's centre, so at a 50 % threshold a horizontal edge decides a cell exactly as a vertical one does.
// protocol/artwork.md says what this means for a feature's width in cells.
import { isEmptyBox, paint, unionBox, EMPTY_BOX, type BoxMm, type Paint } from './artwork';
import { Intervals, subtract, union, unionAll } from './intervals';
import { isCopper } from './layer-kind';
import type { BoardLayer, BoardSet } from './read-board';
import { isIdentity, orientLayer, type Orientation } from './orient';
import { spanSource, type SpanSource } from './spans';

export const LINES_PER_CELL = 15;
export const DEFAULT_THRESHOLD = 0.5;
/**
 * The widest drill dot: each hole's dot is as wide as the hole up to this. A dot wider than its hole eats the
 * pad's ring (a 0.2 mm via in a 0.45 mm pad), and a pit wider than this centres the bit no better.
 */
export const DEFAULT_DRILL_DOT_MM = 0.4;
/**
 * Ties (an edge exactly on a cell's centre line, or covering exactly the threshold) are settled as if the
 * artwork lay 1 nm left of and 1 nm above where the file puts it: a feature n cells wide whose edges fall on
 * cell centres is n cells wide, not n + 1.
 */
export const TIE_NUDGE_MM = 1e-6;
/** The largest grid side: far past any bed, and a guard against a window given in the wrong units. */
export const MAX_CELLS_PER_SIDE = 20000;
/**
 * The least coverage that exposes a cell, whatever the threshold: the tie nudge leaves a few millionths of a
 * cell beside an edge that lies on a cell boundary, and a threshold of 0 must not expose those.
 */
export const MIN_COVERAGE = 0.001;

export type DrillClear = 'none' | 'unexposed-dot' | 'exposed-dot';

export interface RasteriseOptions {
  /** The layers to expose, by kind or by file name. */
  expose: readonly string[];
  pitchUm: { x: number; y: number };
  /** The covered fraction of a cell from which it is exposed, 0–1 (at least MIN_COVERAGE counts). */
  threshold?: number;
  /** A dot at each drill hole's centre in the copper layers, forced unexposed or exposed so the drill finds the centre. */
  drillClear?: DrillClear;
  /** Every dot this wide; by default as wide as its hole, up to DEFAULT_DRILL_DOT_MM. */
  drillDotMm?: number;
  /** Board millimetres the grid covers (after `orient`); by default every layer's artwork, so all exposures of a board line up. */
  windowMm?: BoxMm;
  /** Mirror and turn the board about its origin before rasterising: a bottom layer seen from above, a board laid at an angle. */
  orient?: Orientation;
}

export interface BoardRaster {
  cols: number;
  rows: number;
  /** 1 where a cell is covered at or past the threshold; row 0 is the top (largest Y), column 0 the left. */
  cells: Uint8Array;
  /** Each cell's covered fraction. */
  coverage: Float32Array;
  /** What the cells cover: the window widened to whole cells to the right and downwards. */
  windowMm: BoxMm;
}

/** Every layer's artwork together: the window that lines up all exposures of a board. */
export function boardBounds(set: BoardSet): BoxMm {
  return set.layers.reduce((b, l) => unionBox(b, l.boundsMm), EMPTY_BOX);
}

interface Compiled {
  sources: SpanSource[];
  clear: boolean[];
  box: BoxMm[];
  /** Per cell row, the paints that reach it, in drawing order (CSR: rows' starts into `index`). */
  rowStart: Int32Array;
  index: Int32Array;
}

export function rasteriseBoard(board: BoardSet, opts: RasteriseOptions): BoardRaster {
  const set = isIdentity(opts.orient) ? board : { ...board, layers: board.layers.map((l) => orientLayer(l, opts.orient!)) };
  const px = opts.pitchUm.x / 1000;
  const py = opts.pitchUm.y / 1000;
  if (!(px > 0 && py > 0)) throw new RangeError(`the cell pitch must be positive, not ${opts.pitchUm.x} × ${opts.pitchUm.y} µm`);
  const threshold = opts.threshold ?? DEFAULT_THRESHOLD;
  if (!(threshold >= 0 && threshold <= 1)) throw new RangeError(`the threshold is a fraction from 0 to 1, not ${threshold}`);
  const least = Math.max(threshold, MIN_COVERAGE) - 1e-9;
  const win = opts.windowMm ?? boardBounds(set);
  const cols = isEmptyBox(win) ? 0 : Math.ceil((win.x1 - win.x0) / px - 1e-9);
  const rows = isEmptyBox(win) ? 0 : Math.ceil((win.y1 - win.y0) / py - 1e-9);
  if (cols > MAX_CELLS_PER_SIDE || rows > MAX_CELLS_PER_SIDE) throw new RangeError(`${cols} × ${rows} cells is more than a bed can hold`);
  const left = win.x0;
  const top = win.y1;
  const windowMm = { x0: left, y0: top - rows * py, x1: left + cols * px, y1: top };
  const coverage = new Float32Array(cols * rows);
  const cells = new Uint8Array(cols * rows);
  if (cols === 0 || rows === 0) return { cols, rows, cells, coverage, windowMm };

  const exposed = set.layers.filter((l) => opts.expose.includes(l.kind) || opts.expose.includes(l.file));
  const grid = { top, py, rows, left, right: windowMm.x1 };
  const copper = exposed.filter((l) => isCopper(l.kind)).map((l) => compile(l.paints, grid));
  const others = exposed.filter((l) => !isCopper(l.kind)).map((l) => compile(l.paints, grid));
  const clearing = opts.drillClear ?? 'none';
  const dots = clearing !== 'none' && copper.length > 0 ? compile(drillDots(set.layers, opts.drillDotMm), grid) : null;

  const L = LINES_PER_CELL;
  const acc = new Float64Array(cols);
  const full = new Int32Array(cols + 1);
  const s = new Scratch();
  const lines: Intervals[] = new Array(L);
  const layer: Intervals[] = new Array(L);
  const dotLines: Intervals[] = new Array(L);
  const area = L * px;
  for (let r = 0; r < rows; r++) {
    acc.fill(0);
    full.fill(0);
    s.reset();
    // The rows' lines lie at the centres of L equal strips, nudged down for ties (TIE_NUDGE_MM).
    const rowTop = top - r * py - TIE_NUDGE_MM;
    for (let j = 0; j < L; j++) lines[j] = s.empty();
    for (const c of copper) {
      scanRow(c, r, rowTop, py / L, layer, s);
      for (let j = 0; j < L; j++) lines[j] = s.union(lines[j], layer[j]);
    }
    if (dots) {
      scanRow(dots, r, rowTop, py / L, dotLines, s);
      for (let j = 0; j < L; j++) {
        if (lines[j].length && dotLines[j].length) lines[j] = clearing === 'unexposed-dot' ? s.subtract(lines[j], dotLines[j]) : s.union(lines[j], dotLines[j]);
      }
    }
    for (const c of others) {
      scanRow(c, r, rowTop, py / L, layer, s);
      for (let j = 0; j < L; j++) lines[j] = s.union(lines[j], layer[j]);
    }
    for (let j = 0; j < L; j++) accumulate(lines[j], left + TIE_NUDGE_MM, px, acc, full);
    let whole = 0;
    for (let c = 0; c < cols; c++) {
      whole += full[c];
      const f = Math.min(1, (acc[c] + whole * px) / area);
      coverage[r * cols + c] = f;
      // The 1e-9 only absorbs rounding (a full cell summing to 0.9999999…); ties are settled by TIE_NUDGE_MM.
      cells[r * cols + c] = f >= least ? 1 : 0;
    }
  }
  return { cols, rows, cells, coverage, windowMm };
}

/**
 * Dots of the given diameter at the holes of every drill layer, exposed or not; along a slot, the dot drawn
 * from one end to the other (a stroke the dot's width).
 */
function drillDots(layers: readonly BoardLayer[], diameterMm: number | undefined): Paint[] {
  // A hole of a tool the file never sized (0) gets the widest dot.
  const radius = (hole: number) => (diameterMm ?? (hole > 0 ? Math.min(hole, DEFAULT_DRILL_DOT_MM) : DEFAULT_DRILL_DOT_MM)) / 2;
  const drills = layers.filter((l) => l.kind === 'drill');
  const holes = drills.flatMap((l) => l.holes).map((h): Paint => {
    const r = radius(h.diameterMm);
    return { shape: { kind: 'circle', cx: h.x, cy: h.y, r }, clear: false, box: { x0: h.x - r, y0: h.y - r, x1: h.x + r, y1: h.y + r } };
  });
  const slots = drills.flatMap((l) => l.slots).map((s) => paint({ kind: 'stadium', x0: s.x0, y0: s.y0, x1: s.x1, y1: s.y1, r: radius(s.diameterMm) }, false));
  return [...holes, ...slots];
}

function compile(paints: readonly Paint[], g: { top: number; py: number; rows: number; left: number; right: number }): Compiled {
  const rowOf = (y: number) => Math.floor((g.top - y) / g.py);
  // Within a run of one polarity the order of drawing does not matter: left to right, the spans of a scan
  // line come nearly sorted, which is what the union sorts fastest. Runs keep their order.
  let run = 0;
  const runOf = paints.map((p, i) => (i > 0 && p.clear !== paints[i - 1].clear ? ++run : run));
  const kept = paints
    .map((p, i) => ({ p, run: runOf[i] }))
    .filter(({ p }) => p.box.x1 > g.left && p.box.x0 < g.right && rowOf(p.box.y1) < g.rows && rowOf(p.box.y0) >= 0)
    .sort((a, b) => a.run - b.run || a.p.box.x0 - b.p.box.x0)
    .map(({ p }) => p);
  const counts = new Int32Array(g.rows + 1);
  const span = (p: Paint) => [Math.max(0, rowOf(p.box.y1)), Math.min(g.rows - 1, rowOf(p.box.y0))];
  for (const p of kept) {
    const [r0, r1] = span(p);
    for (let r = r0; r <= r1; r++) counts[r + 1]++;
  }
  for (let r = 0; r < g.rows; r++) counts[r + 1] += counts[r];
  const fill = counts.slice(0, g.rows);
  const index = new Int32Array(counts[g.rows]);
  kept.forEach((p, i) => {
    const [r0, r1] = span(p);
    for (let r = r0; r <= r1; r++) index[fill[r]++] = i;
  });
  return { sources: kept.map((p) => spanSource(p.shape)), clear: kept.map((p) => p.clear), box: kept.map((p) => p.box), rowStart: counts, index };
}

/**
 * One layer on the lines of one cell row (line j at rowTop − (j + ½)·dy): its paints in order, each run of
 * one polarity unioned and added or taken away. Paint by paint, all its lines at once, so each shape's data
 * is fetched once per row.
 */
function scanRow(c: Compiled, row: number, rowTop: number, dy: number, out: Intervals[], s: Scratch): void {
  const L = out.length;
  for (let j = 0; j < L; j++) out[j] = s.empty();
  const runs = s.runs(L);
  const end = c.rowStart[row + 1];
  for (let k = c.rowStart[row]; k < end; ) {
    const clear = c.clear[c.index[k]];
    let touched = false;
    for (; k < end && c.clear[c.index[k]] === clear; k++) {
      const i = c.index[k];
      const b = c.box[i];
      const first = Math.max(0, Math.ceil((rowTop - b.y1) / dy - 0.5));
      const last = Math.min(L - 1, Math.floor((rowTop - b.y0) / dy - 0.5));
      const source = c.sources[i];
      for (let j = first; j <= last; j++) {
        if (clear && out[j].length === 0) continue; // nothing to clear yet
        source.spans(rowTop - (j + 0.5) * dy, runs[j]);
        touched = true;
      }
    }
    if (!touched) continue;
    for (let j = 0; j < L; j++) {
      const run = runs[j];
      if (run.length === 0) continue;
      const set = unionAll(run, s.temp());
      out[j] = clear ? s.subtract(out[j], set) : s.union(out[j], set);
      run.length = 0;
    }
  }
}

/**
 * Adds the lengths of the intervals within each cell of the row: the cut cells at an interval's ends to
 * `acc`, and the cells it covers whole as a count of lines, kept as differences in `full` (+1 where a run of
 * whole cells starts, −1 after it ends), so a wide pour costs two entries, not one per cell.
 */
function accumulate(line: Intervals, left: number, px: number, acc: Float64Array, full: Int32Array): void {
  const cols = acc.length;
  const right = left + cols * px;
  for (let k = 0; k < line.length; k += 2) {
    const a = Math.max(line.v[k], left);
    const b = Math.min(line.v[k + 1], right);
    if (!(b > a)) continue;
    const c0 = Math.min(cols - 1, Math.floor((a - left) / px));
    const c1 = Math.min(cols - 1, Math.floor((b - left) / px));
    if (c0 === c1) {
      acc[c0] += b - a;
      continue;
    }
    acc[c0] += left + (c0 + 1) * px - a;
    if (c1 > c0 + 1) {
      full[c0 + 1]++;
      full[c1]--;
    }
    acc[c1] += b - (left + c1 * px);
  }
}

/** Interval lists reused from line to line, so scanning allocates nothing once warm. */
class Scratch {
  #pool: Intervals[] = [];
  #used = 0;
  #runs: Intervals[] = [];

  /** Lists handed out stay valid until `reset`, at the start of the next cell row. */
  empty(): Intervals {
    return this.temp();
  }

  temp(): Intervals {
    if (this.#used === this.#pool.length) this.#pool.push(new Intervals());
    const l = this.#pool[this.#used++];
    l.length = 0;
    return l;
  }

  /** One list per line of a row to gather a run's spans in, each empty. */
  runs(n: number): Intervals[] {
    while (this.#runs.length < n) this.#runs.push(new Intervals());
    for (const r of this.#runs) r.length = 0;
    return this.#runs;
  }

  union(a: Intervals, b: Intervals): Intervals {
    if (a.length === 0) return b;
    if (b.length === 0) return a;
    return union(a, b, this.temp());
  }

  subtract(a: Intervals, b: Intervals): Intervals {
    return b.length === 0 ? a : subtract(a, b, this.temp());
  }

  reset(): void {
    this.#used = 0;
  }
}
