// Objects cut by the bed's edge, alike for every kind: how far each lies past each edge, and how
// many of the cells it exposes fall off the bed and will not be exposed. The dry run names them.

import { ARTWORK_WORDS, exposes, isArtwork, type Rect, type StudioObject } from './objects';
import type { Raster } from './raster';

/** Cells past each edge of a cols × rows bed (0 where it does not reach it). */
export interface Overhang {
  left: number;
  right: number;
  top: number;
  bottom: number;
}

export interface Cut {
  id: number;
  /** "picture board.png", "SVG logo.svg", "text “rev 2”", "frame". */
  name: string;
  overhangMm: Overhang;
  /** Cells the object exposes that lie off the bed, and all it exposes. */
  lost: number;
  lit: number;
}

export function overhang(o: Rect, cols: number, rows: number): Overhang {
  return { left: Math.max(0, -o.x), right: Math.max(0, o.x + o.w - cols), top: Math.max(0, -o.y), bottom: Math.max(0, o.y + o.h - rows) };
}

export function isOffBed(o: Rect, cols: number, rows: number): boolean {
  return o.x < 0 || o.y < 0 || o.x + o.w > cols || o.y + o.h > rows;
}

export function objectName(o: StudioObject): string {
  if (isArtwork(o)) return `${ARTWORK_WORDS[o.kind]} ${o.name}`;
  if (o.kind === 'text') return `text “${o.text.length > 20 ? `${o.text.slice(0, 19)}…` : o.text}”`;
  return 'frame';
}

/**
 * The exposing objects that lose exposed cells off the bed. An object whose box overhangs only
 * with cells it does not expose (white margin) is not cut. A raster still being read counts its whole box.
 */
export function cutsOf(objects: readonly StudioObject[], raster: (o: StudioObject) => Raster | null, cols: number, rows: number, pitchUm: { x: number; y: number }): Cut[] {
  const cuts: Cut[] = [];
  for (const o of objects) {
    if (!exposes(o) || !isOffBed(o, cols, rows)) continue;
    const r = raster(o);
    let lost = 0, lit = 0;
    for (let y = 0; y < o.h; y++)
      for (let x = 0; x < o.w; x++) {
        if (r && !r[y * o.w + x]) continue;
        lit++;
        const bx = o.x + x, by = o.y + y;
        if (bx < 0 || by < 0 || bx >= cols || by >= rows) lost++;
      }
    if (!lost) continue;
    const c = overhang(o, cols, rows), mm = (cells: number, axis: 'x' | 'y') => (cells * pitchUm[axis]) / 1000;
    cuts.push({ id: o.id, name: objectName(o), overhangMm: { left: mm(c.left, 'x'), right: mm(c.right, 'x'), top: mm(c.top, 'y'), bottom: mm(c.bottom, 'y') }, lost, lit });
  }
  return cuts;
}

/** "12 mm past the right edge, 3.25 mm past the bottom". */
export function overhangWords(mm: Overhang): string {
  const edges: [keyof Overhang, string][] = [['left', 'the left edge'], ['right', 'the right edge'], ['top', 'the top'], ['bottom', 'the bottom']];
  return edges.filter(([k]) => mm[k] > 0).map(([k, words]) => `${+mm[k].toFixed(2)} mm past ${words}`).join(', ');
}

/** "picture board.png: 12 mm past the right edge; 38 % of its exposed cells are off the bed". */
export function cutWords(c: Cut): string {
  const share = Math.max(1, Math.round((100 * c.lost) / c.lit));
  return `${c.name}: ${overhangWords(c.overhangMm)}; ${share} % of its exposed cells are off the bed`;
}
