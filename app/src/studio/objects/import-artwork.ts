// A file picked for import, read as artwork at its true size (loaded on demand): an SVG at the size
// its units state, a picture at the resolution its header states. Where the file states neither,
// the size waits for a resolution the user gives (prefilled with the last one used), never a
// size guessed. Line art (SVG, black-and-white pictures) is exposed by coverage; a greyscale
// picture is dithered.

import { NEUTRAL_TONE } from '../image/adjust';
import { densityOf, type Density } from '../image/density';
import { isLineArt } from '../image/gray';
import { svgSize } from '../image/svg-size';
import { bitmapArtwork, ready } from './artwork';
import type { ArtworkObject, Rect } from './objects';
import { checkSize, dataUrl, readPicture } from './picture';
import type { ReadyArtwork } from './raster';

export interface ImportedArtwork {
  kind: ArtworkObject['kind'];
  name: string;
  src: string;
  artwork: ReadyArtwork;
  /** The size in mm the file states: a picture's pixels at its resolution, an SVG's physical units. Null: ask. */
  sizeMm: { x: number; y: number } | null;
  /** The resolution a picture's header states. */
  dpi: Density | null;
  lineArt: boolean;
}

const INCH_MM = 25.4;
/** The resolution offered when none was used before: a common export resolution for boards. */
const FIRST_DPI = 600;
const LAST_DPI_KEY = 'uv-exposure.import-dpi';

const isSvg = (file: File) => file.type === 'image/svg+xml' || /\.svg$/i.test(file.name);

export async function importArtwork(file: File): Promise<ImportedArtwork> {
  checkSize(file);
  if (isSvg(file)) {
    const size = svgSize(await file.text()); // a file that is no SVG drawing is refused here
    const src = await dataUrl(new Blob([file], { type: 'image/svg+xml' }));
    const { svgArtwork } = await import('./svg-artwork');
    return { kind: 'svg', name: file.name, src, artwork: ready(await svgArtwork(src)), sizeMm: size.mm, dpi: null, lineArt: true };
  }
  const dpi = densityOf(new Uint8Array(await file.slice(0, 256 * 1024).arrayBuffer()));
  const { src, gray } = await readPicture(file);
  const art = bitmapArtwork(gray);
  return { kind: 'image', name: file.name, src, artwork: ready(art), sizeMm: dpi && mmAt(art.pixels, dpi), dpi, lineArt: isLineArt(gray) };
}

/** The size in mm of `pixels` at a resolution in DPI. */
export function mmAt(pixels: { width: number; height: number }, dpi: Density): { x: number; y: number } {
  return { x: (pixels.width / dpi.x) * INCH_MM, y: (pixels.height / dpi.y) * INCH_MM };
}

/** Cells for a size in mm at the machine's pitch: within half a cell of it. */
export function cellsFor(mm: { x: number; y: number }, pitchUm: { x: number; y: number }): { w: number; h: number } {
  return { w: Math.max(1, Math.round((mm.x * 1000) / pitchUm.x)), h: Math.max(1, Math.round((mm.y * 1000) / pitchUm.y)) };
}

/** The new object: line art by a 50 % coverage threshold, a greyscale picture by Floyd–Steinberg. */
export function artworkObject(a: ImportedArtwork, box: Rect): Omit<ArtworkObject, 'id'> {
  return { kind: a.kind, ...box, name: a.name, src: a.src, halftone: a.lineArt ? 'threshold' : 'floyd-steinberg', threshold: 50, tone: { ...NEUTRAL_TONE } };
}

/** The resolution last given for a file that stated none. */
export function lastDpi(): number {
  const v = Number(globalThis.localStorage?.getItem(LAST_DPI_KEY));
  return v > 0 ? v : FIRST_DPI;
}

export function rememberDpi(dpi: number): void {
  globalThis.localStorage?.setItem(LAST_DPI_KEY, String(dpi));
}
