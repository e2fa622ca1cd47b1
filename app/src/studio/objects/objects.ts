// What a project places on the bed besides the painted cells (seed 004's project model): artwork
// read from a file (pictures, SVG drawings), text and frames, each a box in cells that can be
// selected, moved, resized, turned and mirrored. Objects are immutable: a change makes a new one,
// so undo keeps the old list and rasters are cached by content.

import type { Tone } from '../image/adjust';
import type { Halftone } from '../image/halftones';

/** A box of cells: its top-left cell and its size. */
export interface Rect {
  x: number;
  y: number;
  w: number;
  h: number;
}

/** Quarter turns clockwise. */
export type Turn = 0 | 1 | 2 | 3;

/**
 * How an object lies on the bed: its box (as turned) and how its artwork is turned and mirrored.
 * Every kind draws itself upright in its own frame; the turn and the mirror are applied to its
 * cells after (orientation.ts), so every kind turns and mirrors alike.
 */
interface Placed extends Rect {
  id: number;
  /** Quarter turns clockwise, after the mirror; none when absent. */
  turn?: Turn;
  /** Mirrored left to right, before the turn. */
  mirror?: boolean;
}

/**
 * Artwork read from a file, exposed by coverage: each cell by the share of it the artwork covers
 * (a dark pixel, an SVG shape, a Gerber flash), through the tone and the halftone. A threshold
 * exposes a cell whose share reaches it; a dither spreads the greys.
 */
interface ArtworkFields {
  name: string;
  /** The file as imported, as a data: URL: a saved project carries it. */
  src: string;
  halftone: Halftone;
  /** The threshold halftone's cut: a cell is exposed when the artwork covers at least this share of it, percent. */
  threshold: number;
  tone: Tone;
}

/** A picture: PNG, JPEG, BMP, GIF or WebP. */
export interface ImageObject extends Placed, ArtworkFields {
  kind: 'image';
}

/** An SVG drawing, drawn again at every size. */
export interface SvgObject extends Placed, ArtworkFields {
  kind: 'svg';
}

/** What a board's file is, as the user settles it (app/src/pcb's LayerKind, which loads on demand). */
export type BoardLayerKind = 'copper-top' | 'copper-bottom' | 'mask-top' | 'mask-bottom' | 'silk-top' | 'silk-bottom' | 'paste-top' | 'paste-bottom' | 'outline' | 'drill' | 'other';
export const BOARD_LAYER_KINDS: readonly BoardLayerKind[] = ['copper-top', 'copper-bottom', 'mask-top', 'mask-bottom', 'silk-top', 'silk-bottom', 'paste-top', 'paste-bottom', 'outline', 'drill', 'other'];

/** What a drill hole leaves in the copper: nothing, or a dot of resist unexposed or exposed so the drill centres itself. */
export type DrillClear = 'none' | 'unexposed-dot' | 'exposed-dot';
export const DRILL_CLEARS: readonly DrillClear[] = ['none', 'unexposed-dot', 'exposed-dot'];

/**
 * A board's Gerber and Excellon files as one object, drawn over the window of all its layers so
 * every exposure of the board lines up. `src` embeds the files; which of them expose, what each
 * is, the drill dots and the registration marks are the object's own.
 */
export interface BoardObject extends Placed, ArtworkFields {
  kind: 'board';
  /** Each file of `src`, in order: its name, its kind (guessed from the name, then the user's) and whether it is exposed. */
  layers: { file: string; kind: BoardLayerKind; expose: boolean }[];
  drillClear: DrillClear;
  /** Registration marks, mm from the board window's lower left corner (Y up, as in the files): a copper ring with a bare centre to drill. */
  marks: { x: number; y: number }[];
  /** Left out of the job while the board's other side is exposed: drawn by its outline only. */
  leftOut?: boolean;
  /** The file taken for the top copper from what it draws, as no file said it was copper; said on the board until the user sets a layer. */
  copperGuessed?: string;
}

export type ArtworkObject = ImageObject | SvgObject | BoardObject;

export const ARTWORK_KINDS: ArtworkObject['kind'][] = ['image', 'svg', 'board'];

/** Each artwork kind in words, as its panel and the dry run name it. */
export const ARTWORK_WORDS: Record<ArtworkObject['kind'], string> = { image: 'picture', svg: 'SVG', board: 'board' };

export function isArtwork(o: StudioObject): o is ArtworkObject {
  return (ARTWORK_KINDS as string[]).includes(o.kind);
}

export interface TextObject extends Placed {
  kind: 'text';
  /** One or more lines. */
  text: string;
  /** A CSS font family: a system font's name or a generic family. */
  font: string;
  bold: boolean;
  dose: number;
}

/** A rectangle: a guide for placing things when `line` is 0, else an exposed outline `line` cells wide. */
export interface FrameObject extends Placed {
  kind: 'frame';
  line: number;
  dose: number;
}

export type StudioObject = ArtworkObject | TextObject | FrameObject;

export type Corner = 'nw' | 'ne' | 'sw' | 'se';
export const CORNERS: Corner[] = ['nw', 'ne', 'sw', 'se'];

/** Whether the object puts any light on the bed (a guide frame does not). */
export function exposes(o: StudioObject): boolean {
  return o.kind === 'frame' ? o.line > 0 && o.dose > 0 : o.kind === 'text' ? o.dose > 0 && o.text.trim() !== '' : o.kind === 'board' ? !o.leftOut : true;
}

/** Artwork and text keep their proportions when resized; a frame is any rectangle. */
export function keepsAspect(o: StudioObject): boolean {
  return o.kind !== 'frame';
}

/**
 * The topmost object under the cell point (x, y), or null. A frame is hollow: it is hit only on
 * its border, within `edge` cells (the pointer's reach) or its line, so what it frames stays reachable.
 */
export function objectAt(objects: readonly StudioObject[], x: number, y: number, edge = 0): StudioObject | null {
  for (let i = objects.length - 1; i >= 0; i--) {
    const o = objects[i];
    if (o.kind === 'frame') {
      const e = Math.max(edge, o.line);
      const near = x >= o.x - e && y >= o.y - e && x < o.x + o.w + e && y < o.y + o.h + e;
      const inner = x >= o.x + e && y >= o.y + e && x < o.x + o.w - e && y < o.y + o.h - e;
      if (near && !inner) return o;
    } else if (x >= o.x && y >= o.y && x < o.x + o.w && y < o.y + o.h) return o;
  }
  return null;
}

/** The corner's point in cells. */
export function cornerOf(r: Rect, c: Corner): { x: number; y: number } {
  return { x: c[1] === 'w' ? r.x : r.x + r.w, y: c[0] === 'n' ? r.y : r.y + r.h };
}

const OPPOSITE: Record<Corner, Corner> = { nw: 'se', ne: 'sw', sw: 'ne', se: 'nw' };

/**
 * The box after dragging `corner` of `from` to the cell point p, the opposite corner staying put.
 * With `aspect`, the size follows whichever side was dragged further, in proportion.
 */
export function resized(from: Rect, corner: Corner, p: { x: number; y: number }, aspect: boolean): Rect {
  const fixed = cornerOf(from, OPPOSITE[corner]);
  let w = Math.max(1, Math.round(Math.abs(p.x - fixed.x)));
  let h = Math.max(1, Math.round(Math.abs(p.y - fixed.y)));
  if (aspect) {
    const s = Math.max(w / from.w, h / from.h);
    w = Math.max(1, Math.round(from.w * s));
    h = Math.max(1, Math.round(from.h * s));
  }
  const west = corner[1] === 'w', north = corner[0] === 'n';
  return { x: west ? fixed.x - w : fixed.x, y: north ? fixed.y - h : fixed.y, w, h };
}

/** The box moved by (dx, dy) cells, kept so that at least part of it stays on a cols × rows bed. */
export function moved(r: Rect, dx: number, dy: number, cols: number, rows: number): Rect {
  const x = Math.min(cols - 1, Math.max(1 - r.w, r.x + Math.round(dx)));
  const y = Math.min(rows - 1, Math.max(1 - r.h, r.y + Math.round(dy)));
  return { ...r, x, y };
}

/** A box of `w` × `h` cells centred on (cx, cy), kept on the bed where it fits. */
export function centredAt(cx: number, cy: number, w: number, h: number, cols: number, rows: number): Rect {
  const x = Math.max(0, Math.min(cols - w, Math.round(cx - w / 2)));
  const y = Math.max(0, Math.min(rows - h, Math.round(cy - h / 2)));
  return { x, y, w, h };
}
