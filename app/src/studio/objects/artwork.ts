// Artwork read from a file and exposed by coverage (loaded on demand): each kind of file gives an
// Artwork that draws itself at any size in cells, each cell's grey the share of it left bare by
// area; the object's tone and halftone then make doses (a threshold exposes a cell whose covered
// share reaches it). A picture's pixels are averaged over each cell; an SVG is drawn supersampled
// and averaged (svg-artwork.ts).
//
// A board's Gerber and Excellon files are one object (kind 'board', pcb/board-artwork.ts): its cover
// follows the object's layers, drill dots and marks.
//
// A new kind plugs in here: its object type in objects.ts (ArtworkFields
// and its own kind, added to ArtworkObject, ARTWORK_KINDS and ARTWORK_WORDS), a reader in remote-artwork.ts
// (readArtwork) and the work worker (work/artwork-work.ts) giving an Artwork whose cover(w, h) rasterises it over w × h cells by area coverage, its
// `src` pattern in project-file.ts, and its files recognised by import-artwork.ts with their size
// in mm. Turning, mirroring, polarity, the threshold and clipping then apply to it unchanged.

import { adjust } from '../image/adjust';
import { toDoses } from '../image/dither';
import { resample, type Gray } from '../image/gray';
import type { ArtworkObject, BoardObject } from './objects';
import type { ReadyArtwork } from './raster';

export interface Artwork {
  /** Its own size: a picture's pixels, an SVG's CSS pixels (what a resolution in DPI applies to); a board's window in µm. */
  pixels: { width: number; height: number };
  /** w × h cells, row 0 first, each the share of it the artwork leaves bare, by area: 0 all covered … 255 bare. A board draws what `o` chooses. */
  cover(w: number, h: number, o: ArtworkObject): Gray;
}

/**
 * The threshold's cut in darkness, 1 … 255: a cell whose covered share reaches `percent` is
 * exposed, to the nearest of the 255 levels a cell's grey has (exactly half covered reaches 50 %).
 */
export function cutOf(percent: number): number {
  return Math.min(255, Math.max(1, Math.round((percent * 255) / 100)));
}

/** The artwork as the editor takes it: doses at any size through the object's tone, halftone and threshold. */
export function ready(a: Artwork): ReadyArtwork {
  return { pixels: a.pixels, doses: (o, w, h) => toDoses(adjust(a.cover(w, h, o), o.tone), o.halftone, cutOf(o.threshold)) };
}

/** A picture: each cell the mean of the pixels it covers, in proportion to how much of each it covers. */
export function bitmapArtwork(gray: Gray): Artwork {
  return { pixels: { width: gray.width, height: gray.height }, cover: (w, h) => resample(gray, w, h) };
}

/** A board read by app/src/pcb (loaded on demand): drawn over its window with the object's choices. */
export function boardReader(b: { windowMm: { x0: number; y0: number; x1: number; y1: number }; cover(w: number, h: number, look: BoardObject): Gray }): Artwork {
  const w = b.windowMm;
  return { pixels: { width: Math.round((w.x1 - w.x0) * 1000), height: Math.round((w.y1 - w.y0) * 1000) }, cover: (cw, ch, o) => b.cover(cw, ch, o as BoardObject) };
}
