// A file picked for import, read as artwork at its true size (loaded on demand): an SVG at the size
// its units state, a picture at the resolution its header states. Where the file states neither,
// the size waits for a resolution the user gives (prefilled with the last one used), never a
// size guessed. Line art (SVG, black-and-white pictures) is exposed by coverage; a greyscale
// picture is dithered.

import { NEUTRAL_TONE } from '../image/adjust';
import { densityOf, type Density } from '../image/density';
import { svgSize } from '../image/svg-size';
import type { CallOptions } from '../../work/work-client';
import { ready } from './artwork';
import { newBoardFields, type NewBoardFields } from './board-object';
import type { NewObject } from './object-layer.svelte';
import type { FileProblems } from '../../pcb/problem-words';
import type { ArtworkObject, Rect } from './objects';
import { checkSize, dataUrl } from './picture';
import { readBoard, readPicture, remoteArtwork } from './remote-artwork';
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
  /** A board's layers, drill dots and marks as first chosen. */
  board?: NewBoardFields;
  /** A board's files that could not be read, or not wholly, and why, one entry a file: the rest is placed. */
  problems?: FileProblems[];
  /** A board's files that draw nothing, as is normal for their kind: said quietly, one entry a file. */
  notes?: FileProblems[];
}

const INCH_MM = 25.4;
/** The resolution offered when none was used before: a common export resolution for boards. */
const FIRST_DPI = 600;
const LAST_DPI_KEY = 'uv-exposure.import-dpi';

const PICTURE = /\.(svg|png|jpe?g|bmp|gif|webp)$/i;

/** Linux's shared MIME database calls a .gbr a GIMP brush (image/x-gimp-gbr): its name says Gerber first. */
const GERBER_NAME = /\.gbr$/i;

const isPicture = (f: File) => PICTURE.test(f.name) || (f.type.startsWith('image/') && !GERBER_NAME.test(f.name));

/** Several files at once, or one that is no picture or drawing (a .gbr, .gtl, .drl…): a board's files. */
export const isBoardPick = (files: readonly File[]): boolean => files.length > 1 || (files.length === 1 && !isPicture(files[0]));

/** A board's files as one object at the size of its window, each file's kind guessed from what it says and draws (read in the worker). */
export async function importBoard(files: readonly File[], opts?: CallOptions): Promise<ImportedArtwork> {
  for (const f of files) checkSize(f);
  const texts = await Promise.all(files.map(async (f) => ({ name: f.name, text: await f.text() })));
  const board = await readBoard({ files: texts }, opts); // refused when nothing in the files draws
  const mm = { x: board.pixels.width / 1000, y: board.pixels.height / 1000 };
  return { kind: 'board', name: boardName(texts.map((t) => t.name)), src: board.src, artwork: remoteArtwork(board.pixels), sizeMm: mm, dpi: null, lineArt: true, board: newBoardFields(board.kinds), problems: board.problems, notes: board.notes };
}

/** What the files' names share (KiCad's "board-F_Cu.gbr", "board-PTH.drl": "board"), else the first name. */
export function boardName(names: readonly string[]): string {
  let common = names[0] ?? 'board';
  for (const n of names) while (!n.startsWith(common)) common = common.slice(0, -1);
  common = common.replace(/[-_. ]+$/, '');
  return common.length >= 2 ? common : (names[0] ?? 'board');
}

const isSvg = (file: File) => file.type === 'image/svg+xml' || /\.svg$/i.test(file.name);

export async function importArtwork(file: File, opts?: CallOptions): Promise<ImportedArtwork> {
  checkSize(file);
  if (isSvg(file)) {
    const size = svgSize(await file.text()); // a file that is no SVG drawing is refused here
    const src = await dataUrl(new Blob([file], { type: 'image/svg+xml' }));
    const { svgArtwork } = await import('./svg-artwork');
    return { kind: 'svg', name: file.name, src, artwork: ready(await svgArtwork(src)), sizeMm: size.mm, dpi: null, lineArt: true };
  }
  const dpi = densityOf(new Uint8Array(await file.slice(0, 256 * 1024).arrayBuffer()));
  const src = await dataUrl(file);
  const { pixels, lineArt } = await readPicture(src, opts); // decoded in the worker, where it stays
  return { kind: 'image', name: file.name, src, artwork: remoteArtwork(pixels), sizeMm: dpi && mmAt(pixels, dpi), dpi, lineArt };
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
export function artworkObject(a: ImportedArtwork, box: Rect): NewObject {
  if (a.kind === 'board') return { kind: 'board', ...box, name: a.name, src: a.src, halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE }, ...(a.board ?? newBoardFields([])) };
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
