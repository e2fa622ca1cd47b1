// Objects as doses: each object rasterised at its box's size, and the project composed from the
// painted grid and its objects for the planner. Where things overlap the greater dose wins, so a
// picture's white background never erases what lies under it.

import { adjust } from '../image/adjust';
import { toDoses } from '../image/dither';
import { resample, type Gray } from '../image/gray';
import { DoseGrid } from '../grid/grid';
import { exposes, type FrameObject, type ImageObject, type Rect, type StudioObject, type TextObject } from './objects';

/** The cells' doses of an object, w × h, row 0 first. */
export type Raster = Uint8Array;

export function frameRaster(o: FrameObject): Raster {
  const out = new Uint8Array(o.w * o.h);
  const t = Math.min(o.line, Math.ceil(o.w / 2), Math.ceil(o.h / 2));
  for (let y = 0; y < o.h; y++)
    for (let x = 0; x < o.w; x++) if (x < t || y < t || x >= o.w - t || y >= o.h - t) out[y * o.w + x] = o.dose;
  return out;
}

export function imageRaster(o: ImageObject, source: Gray): Raster {
  return toDoses(adjust(resample(source, o.w, o.h), o.tone), o.halftone, o.level);
}

/** What each kind needs from outside pure code: a picture's decoded pixels, text drawn by the browser. */
export interface RasterSources {
  gray(src: string): Gray | undefined;
  text(o: TextObject): Raster;
}

export function rasterOf(o: StudioObject, sources: RasterSources): Raster | null {
  if (o.kind === 'frame') return frameRaster(o);
  if (o.kind === 'text') return sources.text(o);
  const g = sources.gray(o.src);
  return g ? imageRaster(o, g) : null;
}

/**
 * The cells the planner exposes: the painted grid with every exposing object laid over it, each
 * clipped to the bed. The painted grid itself comes back when no object exposes anything.
 */
export function compose(paint: DoseGrid, objects: readonly StudioObject[], raster: (o: StudioObject) => Raster | null): DoseGrid {
  const lit = objects.filter(exposes);
  if (lit.length === 0) return paint;
  const out = new DoseGrid(paint.cols, paint.rows, paint.cells.slice());
  for (const o of lit) {
    const r = raster(o);
    if (r) layOver(out, o, r);
  }
  return out;
}

/**
 * Lays an object's raster over the grid where its box lies, the greater dose winning in each cell,
 * clipped to the grid; returns the cells it covered, or null if none are on the grid.
 */
export function layOver(grid: DoseGrid, o: Rect, r: Raster): { x0: number; y0: number; x1: number; y1: number } | null {
  const x0 = Math.max(0, o.x), x1 = Math.min(grid.cols, o.x + o.w) - 1;
  const y0 = Math.max(0, o.y), y1 = Math.min(grid.rows, o.y + o.h) - 1;
  if (x0 > x1 || y0 > y1) return null;
  for (let y = y0; y <= y1; y++) {
    const row = (y - o.y) * o.w - o.x;
    for (let x = x0; x <= x1; x++) {
      const d = r[row + x];
      if (d > grid.cells[y * grid.cols + x]) grid.cells[y * grid.cols + x] = d;
    }
  }
  return { x0, y0, x1, y1 };
}
