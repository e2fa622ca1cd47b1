// Text in the browser's system fonts: measured and drawn on an OffscreenCanvas at the object's
// size in cells, each cell lit where the glyphs cover at least half of it.

import type { Raster } from './raster';
import type { TextObject } from './objects';

/** A line's height over the font's size. */
const LEADING = 1.2;

const GENERIC = new Set(['serif', 'sans-serif', 'monospace', 'cursive', 'fantasy', 'system-ui', 'ui-serif', 'ui-sans-serif', 'ui-monospace', 'ui-rounded']);

/** The CSS font for a text object at `px` pixels: a named family quoted, a generic one not. */
export function cssFont(o: Pick<TextObject, 'font' | 'bold'>, px: number): string {
  const family = o.font.trim() || 'sans-serif';
  const name = GENERIC.has(family) ? family : `"${family.replace(/["\\]/g, '')}", sans-serif`;
  return `${o.bold ? 'bold ' : ''}${px}px ${name}`;
}

export function linesOf(text: string): string[] {
  return text.split(/\r?\n/);
}

function context(w: number, h: number): OffscreenCanvasRenderingContext2D {
  return new OffscreenCanvas(Math.max(1, w), Math.max(1, h)).getContext('2d', { willReadFrequently: true })!;
}

function widest(ctx: OffscreenCanvasRenderingContext2D, lines: string[]): number {
  return Math.max(0, ...lines.map((l) => ctx.measureText(l).width));
}

/** How many cells wide the text is when its box is `h` cells high. */
export function textWidth(o: Pick<TextObject, 'font' | 'bold' | 'text'>, h: number): number {
  const lines = linesOf(o.text);
  const ctx = context(1, 1);
  ctx.font = cssFont(o, h / (lines.length * LEADING));
  return Math.max(1, Math.ceil(widest(ctx, lines)));
}

export function textRaster(o: TextObject): Raster {
  const out = new Uint8Array(o.w * o.h);
  const lines = linesOf(o.text);
  const px = o.h / (lines.length * LEADING);
  const ctx = context(o.w, o.h);
  ctx.font = cssFont(o, px);
  const natural = widest(ctx, lines);
  if (natural === 0) return out;
  ctx.scale(o.w / natural, 1); // fills the box: a resize that kept the aspect scales by about 1
  ctx.textBaseline = 'middle';
  ctx.fillStyle = '#000';
  lines.forEach((l, i) => ctx.fillText(l, 0, (i + 0.5) * px * LEADING));
  const alpha = ctx.getImageData(0, 0, o.w, o.h).data;
  for (let i = 0; i < out.length; i++) if (alpha[i * 4 + 3] >= 128) out[i] = o.dose;
  return out;
}
