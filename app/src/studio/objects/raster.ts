// Objects as doses: each object drawn upright in its own frame, turned and mirrored onto its box,
// and the project composed from the painted grid and its objects for the planner. With negative
// resist (dry film) the artwork is what is exposed, and where objects overlap the greater dose
// wins, so a picture's white background never erases what lies under it. With positive resist
// what the artwork does not cover is exposed, and where objects overlap the lesser dose wins, so
// copper drawn by any of them keeps its resist.

import { DoseGrid } from '../grid/grid';
import { exposes, type ArtworkObject, type FrameObject, type Rect, type StudioObject, type TextObject } from './objects';
import { frameSize, orient } from './orientation';

/** The cells' doses of an object, w × h, row 0 first. */
export type Raster = Uint8Array;

/**
 * Sprites made off the page's thread (the work worker draws a large raster's as an ImageBitmap),
 * known by the raster they show; the editor draws them instead of making its own. Kept here, with
 * the rasters of the first load: in a file of its own, shared by the studio's and the panels'
 * chunks, its 141 B took a 4 KB block of the ESP's flash.
 */
export const madeSprites = new WeakMap<Raster, CanvasImageSource>();

/** Which side of the artwork is exposed, for the whole job. */
export type Polarity = 'negative' | 'positive';

/**
 * An object's artwork once read (on-demand code decodes it): what any artwork kind gives the
 * editor. Its doses come from coverage: how much of each cell the artwork covers.
 */
export interface ReadyArtwork {
  /** Its own size: a picture's pixels, an SVG's CSS pixels; what a resolution in DPI applies to. */
  pixels: { width: number; height: number };
  /** Doses of w × h cells in its own frame (upright, not mirrored), by its tone, halftone and threshold. */
  doses?(o: ArtworkObject, w: number, h: number): Raster;
  /**
   * Or the object's whole raster made off the page's thread (remote-artwork.ts): null while it is
   * being made; the function given to `whenDrawn` is called each time one is in.
   */
  drawn?(o: ArtworkObject, polarity: Polarity): Raster | null;
  whenDrawn?(redraw: () => void): void;
  /** Waits until the object's raster is in (it throws if it cannot be made). */
  settle?(o: ArtworkObject, polarity: Polarity): Promise<void>;
}

export function frameRaster(o: Pick<FrameObject, 'w' | 'h' | 'line' | 'dose'>): Raster {
  const out = new Uint8Array(o.w * o.h);
  const t = Math.min(o.line, Math.ceil(o.w / 2), Math.ceil(o.h / 2));
  for (let y = 0; y < o.h; y++)
    for (let x = 0; x < o.w; x++) if (x < t || y < t || x >= o.w - t || y >= o.h - t) out[y * o.w + x] = o.dose;
  return out;
}

/** What each kind needs from outside pure code: artwork read from its file, text drawn by the browser. */
export interface RasterSources {
  artwork(src: string): ReadyArtwork | undefined;
  text(o: TextObject): Raster;
}

/** The dose of an object's solid parts: text and frames have their own, artwork the full dose. */
export function fullDose(o: StudioObject): number {
  return o.kind === 'text' || o.kind === 'frame' ? o.dose : 255;
}

/** The object's exposure on its box, or null while its artwork is still being read. */
export function rasterOf(o: StudioObject, sources: RasterSources, polarity: Polarity = 'negative'): Raster | null {
  const art = o.kind === 'frame' || o.kind === 'text' ? undefined : sources.artwork(o.src);
  if (art?.drawn) return art.drawn(o as ArtworkObject, polarity);
  const { w, h } = frameSize(o);
  const upright = o.kind === 'frame' ? frameRaster({ ...o, w, h }) : o.kind === 'text' ? sources.text({ ...o, w, h }) : (art?.doses?.(o, w, h) ?? null);
  if (!upright) return null;
  const out = orient(upright, w, h, o);
  if (polarity === 'negative') return out;
  const full = fullDose(o);
  return out.map((d) => full - Math.min(full, d));
}

/**
 * The cells the planner exposes: the painted grid with every exposing object laid over it, each
 * clipped to the bed. The painted grid itself comes back when no object exposes anything.
 */
export function compose(paint: DoseGrid, objects: readonly StudioObject[], raster: (o: StudioObject) => Raster | null, polarity: Polarity = 'negative'): DoseGrid {
  const steps = composing(paint, objects, raster, polarity);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return step.value;
}

/** The same, with the page's other tasks let run (`pause`) after the copy and after each object. */
export async function composeSoon(paint: DoseGrid, objects: readonly StudioObject[], raster: (o: StudioObject) => Raster | null, polarity: Polarity, pause: () => Promise<unknown>): Promise<DoseGrid> {
  const steps = composing(paint, objects, raster, polarity);
  let step = steps.next();
  while (!step.done) {
    await pause();
    step = steps.next();
  }
  return step.value;
}

/** The cells a composing step lays at most: a few ms of the page's thread on a busy machine. */
const STEP_CELLS = 1 << 20;

/** An object's rows in bands of about STEP_CELLS cells, the last row of each included. */
function* bandsOf(o: Rect): Generator<[number, number]> {
  const step = Math.max(1, Math.floor(STEP_CELLS / Math.max(1, o.w)));
  for (let y = o.y; y < o.y + o.h; y += step) yield [y, Math.min(o.y + o.h, y + step) - 1];
}

/**
 * compose's steps, each a band of an object's rows: a whole bed's copy and a busy board laid over it
 * were one 85 ms task on a busy machine, the longest of a Gerber board's dry run, and the board alone
 * still 58 ms (issue 40).
 */
function* composing(paint: DoseGrid, objects: readonly StudioObject[], raster: (o: StudioObject) => Raster | null, polarity: Polarity): Generator<void, DoseGrid> {
  const lit = objects.filter(exposes);
  if (lit.length === 0) return paint;
  const out = new DoseGrid(paint.cols, paint.rows);
  for (const [from, to] of bandsOf({ x: 0, y: 0, w: paint.cols, h: paint.rows })) {
    out.cells.set(paint.cells.subarray(from * paint.cols, (to + 1) * paint.cols), from * paint.cols);
    yield; // a whole bed's 16 MB copied in one go, with its fresh memory's page faults, was 94 ms on a busy machine
  }
  if (polarity === 'negative') {
    for (const o of lit) {
      yield;
      const r = raster(o);
      if (r)
        for (const [from, to] of bandsOf(o)) {
          layOver(out, o, r, from, to);
          yield;
        }
    }
    return out;
  }
  const art = new DoseGrid(paint.cols, paint.rows);
  const laid = new Uint8Array(paint.cols * paint.rows);
  for (const o of lit) {
    yield;
    const r = raster(o);
    if (r)
      for (const [from, to] of bandsOf(o)) {
        layUnder(art, laid, o, r, from, to);
        yield;
      }
  }
  for (const [from, to] of bandsOf({ x: 0, y: 0, w: paint.cols, h: paint.rows })) {
    yield;
    for (let i = from * paint.cols; i < (to + 1) * paint.cols; i++) if (art.cells[i] > out.cells[i]) out.cells[i] = art.cells[i];
  }
  return out;
}

/** The object's box within the grid's rows `from`..`to`, or null if none of it is there. */
function onGrid(grid: DoseGrid, o: Rect, from = 0, to = grid.rows - 1): { x0: number; y0: number; x1: number; y1: number } | null {
  const x0 = Math.max(0, o.x), x1 = Math.min(grid.cols, o.x + o.w) - 1;
  const y0 = Math.max(0, from, o.y), y1 = Math.min(to + 1, grid.rows, o.y + o.h) - 1;
  return x0 > x1 || y0 > y1 ? null : { x0, y0, x1, y1 };
}

/**
 * Lays an object's raster over the grid where its box lies, the greater dose winning in each cell,
 * clipped to the grid (and to the grid's rows `from`..`to`); returns the cells it covered, or null if
 * none are on the grid.
 */
export function layOver(grid: DoseGrid, o: Rect, r: Raster, from = 0, to = grid.rows - 1): { x0: number; y0: number; x1: number; y1: number } | null {
  const b = onGrid(grid, o, from, to);
  if (!b) return null;
  // A row at a time with its offsets held: reading grid.cells and y * cols again for every cell, a busy
  // board laid over a whole bed took 62 ms of the page's thread before the dry run (issue 40).
  const cells = grid.cells, cols = grid.cols;
  for (let y = b.y0; y <= b.y1; y++) {
    const from = (y - o.y) * o.w - o.x, to = y * cols;
    for (let x = b.x0; x <= b.x1; x++) {
      const d = r[from + x];
      if (d > cells[to + x]) cells[to + x] = d;
    }
  }
  return b;
}

/** Positive resist: the lesser dose wins where objects overlap (`laid` marks the cells an object already set). */
function layUnder(grid: DoseGrid, laid: Uint8Array, o: Rect, r: Raster, from: number, to: number): void {
  const b = onGrid(grid, o, from, to);
  if (!b) return;
  for (let y = b.y0; y <= b.y1; y++) {
    const row = (y - o.y) * o.w - o.x;
    for (let x = b.x0; x <= b.x1; x++) {
      const i = y * grid.cols + x, d = r[row + x];
      if (!laid[i] || d < grid.cells[i]) grid.cells[i] = d;
      laid[i] = 1;
    }
  }
}
