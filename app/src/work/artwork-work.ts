// The work worker's artwork: pictures decoded and boards read once, kept by their data: URL, and
// each object's doses drawn from them. Every request carries the file itself, so a worker started
// afresh (after a cancel) reads again what it no longer holds.

import { boardArtwork, boardSrc, problemsByFile, BoardUnreadable } from '../pcb';
import { isLineArt } from '../studio/image/gray';
import { bitmapArtwork, boardReader, ready, type Artwork } from '../studio/objects/artwork';
import type { ArtworkObject } from '../studio/objects/objects';
import { grayOf } from '../studio/objects/picture';
import { rasterOf, type Polarity, type Raster } from '../studio/objects/raster';
import type { Progress, BoardRead, PictureRead } from './work-types';
import { doseColours } from '../studio/canvas/tile-cache';
import { spritePixels } from '../studio/canvas/made-sprites';

type Report = (p: Progress) => void;

/** The artworks read lately, the latest last: a 36-megapixel picture holds 36 MB, so only a few. */
const KEPT = 4;
const kept = new Map<string, { artwork: Artwork; lineArt: boolean; board?: BoardRead }>();

function keep(src: string, entry: { artwork: Artwork; lineArt: boolean; board?: BoardRead }) {
  kept.delete(src);
  if (kept.size >= KEPT) kept.delete(kept.keys().next().value!);
  kept.set(src, entry);
  return entry;
}

async function pictureOf(src: string, report: Report) {
  const have = kept.get(src);
  if (have) return have;
  report({ stage: 'decoding the picture' });
  const gray = await grayOf(src);
  report({ stage: 'reading its greys' });
  return keep(src, { artwork: bitmapArtwork(gray), lineArt: isLineArt(gray) });
}

function boardOf(src: string, report: Report) {
  const have = kept.get(src);
  if (have) return have;
  report({ stage: 'reading the board' });
  const board = boardArtwork(src); // throws BoardUnreadable when nothing in the files draws
  const artwork = boardReader(board);
  const kinds = board.files.map((file) => {
    const layer = board.set.layers.find((l) => l.file === file);
    return { file, kind: layer?.kind ?? 'other', from: layer?.kindFrom ?? ('unread' as const) };
  });
  return keep(src, { artwork, lineArt: true, board: { src, pixels: artwork.pixels, kinds, problems: problemsByFile(board.set.problems), notes: problemsByFile(board.set.notes) } });
}

export async function readPicture(src: string, report: Report): Promise<PictureRead> {
  const p = await pictureOf(src, report);
  return { pixels: p.artwork.pixels, lineArt: p.lineArt };
}

export function readBoard(from: { src?: string; files?: { name: string; text: string }[] }, report: Report): BoardRead {
  return boardOf(from.src ?? boardSrc(from.files ?? []), report).board!;
}

const lut = doseColours();

/** The raster as the editor draws it (canvas/draw-objects.ts), made here; null where there is no OffscreenCanvas (Node). */
export function spriteOf(raster: Raster, w: number, h: number): ImageBitmap | null {
  if (typeof OffscreenCanvas === 'undefined' || !raster.length) return null;
  const canvas = new OffscreenCanvas(w, h);
  canvas.getContext('2d')!.putImageData(new ImageData(new Uint8ClampedArray(spritePixels(raster, lut).buffer), w, h), 0, 0);
  return canvas.transferToImageBitmap();
}

/** The object's doses on its box, as the editor would make them on the page. */
export async function rasterInWorker(o: ArtworkObject, polarity: Polarity, report: Report): Promise<Raster> {
  const entry = o.kind === 'board' ? boardOf(o.src, report) : await pictureOf(o.src, report);
  report({ stage: o.kind === 'board' ? 'drawing the board in cells' : 'drawing the picture in cells' });
  const raster = rasterOf(o, { artwork: () => ready(entry.artwork), text: () => new Uint8Array(0) }, polarity);
  if (!raster) throw new Error('the artwork could not be drawn');
  return raster;
}

export { BoardUnreadable };
