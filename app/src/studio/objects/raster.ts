// Objects as doses: each object rasterised at its box's size, and the project composed from the
// painted grid and its objects for the planner. Where things overlap the greater dose wins, so a
// picture's white background never erases what lies under it.

import { adjust } from '../image/adjust';
import { toDoses } from '../image/dither';
import { resample, type Gray } from '../image/gray';
import { DoseGrid } from '../grid/grid';
import { exposes, type FrameObject, type ImageObject, type StudioObject, type TextObject } from './objects';

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
    if (!r) continue;
    const x0 = Math.max(0, o.x), x1 = Math.min(paint.cols, o.x + o.w);
    for (let y = Math.max(0, o.y); y < Math.min(paint.rows, o.y + o.h); y++) {
      const row = (y - o.y) * o.w - o.x;
      for (let x = x0; x < x1; x++) {
        const d = r[row + x];
        if (d > out.cells[y * paint.cols + x]) out.cells[y * paint.cols + x] = d;
      }
    }
  }
  return out;
}
