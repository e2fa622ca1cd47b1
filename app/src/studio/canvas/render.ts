// Draws the editor's view: the bed, the visible tiles at the right level of detail, the cell
// grid when zoomed in, the project's objects, a shape being dragged, and rulers in mm along the top and left.

import type { GridEditor } from '../editor.svelte';
import { drawObjects, type Sprites } from './draw-objects';
import { TILE, type TileCache } from './tile-cache';
import { RULER, rulerStep, toScreen } from './viewport';

/** The rulers' numbers; EditorCanvas readies it before the first frame (ui/later.ts). */
export const RULER_FONT = '10px system-ui, sans-serif';
export const RULER_SAMPLE = 'mm 0123456789.';

/** A frame's time for the coarser levels after an edit: the rest of the frame draws the tiles. */
const LEVELS_MS = 8;

/**
 * Draws a frame; false when the coarser levels still carry an edit (a few ms of it are made per
 * frame, TileCache.catchUp), so the caller draws again in the next frame.
 */
export function render(ctx: CanvasRenderingContext2D, w: number, h: number, ed: GridEditor, cache: TileCache<HTMLCanvasElement>, sprites: Sprites): boolean {
  const caughtUp = cache.catchUp(performance.now() + LEVELS_MS);
  const v = ed.view;
  const { cols, rows } = ed.grid;
  ctx.fillStyle = '#d9dbe3';
  ctx.fillRect(0, 0, w, h);
  const bed = toScreen(v, 0, 0);
  ctx.fillStyle = '#fafafa';
  ctx.fillRect(bed.x, bed.y, cols * v.scale, rows * v.scale);

  ctx.imageSmoothingEnabled = false;
  const k = cache.levelFor(v.scale);
  const f = 1 << k;
  const level = cache.levelsSoFar[k];
  const x0 = Math.max(0, Math.floor(v.x / f / TILE)), x1 = Math.min(Math.ceil(level.cols / TILE) - 1, Math.floor((v.x + w / v.scale) / f / TILE));
  const y0 = Math.max(0, Math.floor(v.y / f / TILE)), y1 = Math.min(Math.ceil(level.rows / TILE) - 1, Math.floor((v.y + h / v.scale) / f / TILE));
  for (let ty = y0; !cache.blank && ty <= y1; ty++) // a bed never painted: its tiles are the bed's colour
    for (let tx = x0; tx <= x1; tx++) {
      const tile = cache.tile(k, tx, ty);
      const at = toScreen(v, tx * TILE * f, ty * TILE * f);
      ctx.drawImage(tile, at.x, at.y, tile.width * f * v.scale, tile.height * f * v.scale);
    }

  if (v.scale >= 8) {  // cell lines once a cell is big enough to aim at
    ctx.strokeStyle = '#0000001a';
    ctx.lineWidth = 1;
    ctx.beginPath();
    const cx0 = Math.max(0, Math.floor(v.x)), cx1 = Math.min(cols, Math.ceil(v.x + w / v.scale));
    const cy0 = Math.max(0, Math.floor(v.y)), cy1 = Math.min(rows, Math.ceil(v.y + h / v.scale));
    for (let x = cx0; x <= cx1; x++) {
      const sx = Math.round(toScreen(v, x, 0).x) + 0.5;
      ctx.moveTo(sx, toScreen(v, 0, cy0).y);
      ctx.lineTo(sx, toScreen(v, 0, cy1).y);
    }
    for (let y = cy0; y <= cy1; y++) {
      const sy = Math.round(toScreen(v, 0, y).y) + 0.5;
      ctx.moveTo(toScreen(v, cx0, 0).x, sy);
      ctx.lineTo(toScreen(v, cx1, 0).x, sy);
    }
    ctx.stroke();
  }

  ctx.strokeStyle = '#2b1d4f';
  ctx.lineWidth = 1;
  ctx.strokeRect(Math.round(bed.x) + 0.5, Math.round(bed.y) + 0.5, Math.round(cols * v.scale), Math.round(rows * v.scale));

  drawObjects(ctx, v, ed.layer, sprites, cols, rows);

  const p = ed.preview;
  if (p) {
    ctx.strokeStyle = '#7a3cff';
    ctx.lineWidth = Math.max(1, ed.size * v.scale);
    const a = toScreen(v, p.x0 + 0.5, p.y0 + 0.5), b = toScreen(v, p.x1 + 0.5, p.y1 + 0.5);
    ctx.beginPath();
    if (ed.tool === 'line') {
      ctx.moveTo(a.x, a.y);
      ctx.lineTo(b.x, b.y);
      ctx.stroke();
    } else if (ed.tool === 'rect-filled') {
      ctx.fillStyle = '#7a3cff55';
      ctx.fillRect(Math.min(a.x, b.x), Math.min(a.y, b.y), Math.abs(b.x - a.x), Math.abs(b.y - a.y));
    } else {
      ctx.strokeRect(Math.min(a.x, b.x), Math.min(a.y, b.y), Math.abs(b.x - a.x), Math.abs(b.y - a.y));
    }
  }
  rulers(ctx, w, h, ed);
  return caughtUp;
}

function rulers(ctx: CanvasRenderingContext2D, w: number, h: number, ed: GridEditor): void {
  const v = ed.view;
  const { pitchUm } = ed.machine;
  ctx.fillStyle = '#f4f5f8ee';
  ctx.fillRect(0, 0, w, RULER);
  ctx.fillRect(0, 0, RULER, h);
  ctx.fillStyle = '#444a5a';
  ctx.strokeStyle = '#444a5a';
  ctx.font = RULER_FONT;
  ctx.lineWidth = 1;
  const pxPerMmX = (v.scale * 1000) / pitchUm.x, pxPerMmY = (v.scale * 1000) / pitchUm.y;
  const stepX = rulerStep(pxPerMmX), stepY = rulerStep(pxPerMmY);
  ctx.beginPath();
  const mmX0 = (v.x * pitchUm.x) / 1000, mmX1 = mmX0 + w / pxPerMmX;
  for (let mm = Math.ceil(mmX0 / stepX) * stepX; mm <= mmX1; mm += stepX) {
    const sx = Math.round((mm - mmX0) * pxPerMmX) + 0.5;
    if (sx < RULER) continue;
    ctx.moveTo(sx, RULER - 6);
    ctx.lineTo(sx, RULER);
    ctx.fillText(`${+mm.toFixed(3)}`, sx + 2, 11);
  }
  const mmY0 = (v.y * pitchUm.y) / 1000, mmY1 = mmY0 + h / pxPerMmY;
  for (let mm = Math.ceil(mmY0 / stepY) * stepY; mm <= mmY1; mm += stepY) {
    const sy = Math.round((mm - mmY0) * pxPerMmY) + 0.5;
    if (sy < RULER + 10) continue; // clear of the corner label
    ctx.moveTo(RULER - 6, sy);
    ctx.lineTo(RULER, sy);
    ctx.save();
    ctx.translate(11, sy + 2);
    ctx.rotate(-Math.PI / 2);
    ctx.fillText(`${+mm.toFixed(3)}`, 0, 0);
    ctx.restore();
  }
  ctx.stroke();
  ctx.fillText('mm', 2, 11);
}
