// Draws the project's objects over the painted cells: each as the doses it will expose (a sprite
// made from its raster, remade only when the raster is), a guide frame dashed, every object's
// box faintly, an object cut by the bed's edge in red, and the selection with its corner handles.

import type { ObjectLayer } from '../objects/object-layer.svelte';
import { exposes, type StudioObject } from '../objects/objects';
import { FRAME_PX, HANDLE_PX, handleCentres, selectionFrame } from './handles';
import { madeSprites, type Raster } from '../objects/raster';
import { doseColours } from './tile-cache';
import { spritePixels } from './made-sprites';
import { toScreen, type View } from './viewport';

const ACCENT = '#7a3cff';

export class Sprites {
  #kept = new Map<number, { raster: Raster; canvas: CanvasImageSource }>();
  readonly #lut = doseColours();

  /** The raster as a canvas of its cells, dose 0 see-through; a large artwork's comes made by the work worker. */
  of(id: number, raster: Raster, w: number, h: number): CanvasImageSource {
    const kept = this.#kept.get(id);
    if (kept?.raster === raster) return kept.canvas;
    const made = madeSprites.get(raster);
    if (made) {
      this.#kept.set(id, { raster, canvas: made });
      return made;
    }
    const canvas = Object.assign(document.createElement('canvas'), { width: w, height: h });
    const pixels = spritePixels(raster, this.#lut);
    canvas.getContext('2d')!.putImageData(new ImageData(new Uint8ClampedArray(pixels.buffer), w, h), 0, 0);
    this.#kept.set(id, { raster, canvas });
    return canvas;
  }

  /** Lets go of the sprites of objects no longer on the layer (a deleted picture's can be large). */
  keepOnly(objects: readonly StudioObject[]): void {
    const ids = new Set(objects.map((o) => o.id));
    for (const id of this.#kept.keys()) if (!ids.has(id)) this.#kept.delete(id);
  }
}

/** An exposing object past the bed's edge (cols × rows): the part off the bed hatched red, its box red. */
function drawOffBed(ctx: CanvasRenderingContext2D, v: View, o: StudioObject, cols: number, rows: number): boolean {
  if (!exposes(o) || (o.x >= 0 && o.y >= 0 && o.x + o.w <= cols && o.y + o.h <= rows)) return false;
  const at = toScreen(v, o.x, o.y), bed = toScreen(v, 0, 0);
  ctx.save();
  ctx.beginPath();
  ctx.rect(at.x, at.y, o.w * v.scale, o.h * v.scale);
  ctx.clip();
  ctx.beginPath();
  ctx.rect(at.x - 1, at.y - 1, o.w * v.scale + 2, o.h * v.scale + 2);
  ctx.rect(bed.x, bed.y, cols * v.scale, rows * v.scale);
  ctx.fillStyle = '#d3262666';
  ctx.fill('evenodd');
  ctx.restore();
  ctx.strokeStyle = '#d32626';
  ctx.setLineDash([]);
  return true;
}

export function drawObjects(ctx: CanvasRenderingContext2D, v: View, layer: ObjectLayer, sprites: Sprites, cols: number, rows: number): void {
  ctx.imageSmoothingEnabled = false;
  for (const o of layer.objects) {
    const at = toScreen(v, o.x, o.y), w = o.w * v.scale, h = o.h * v.scale;
    if (exposes(o)) {
      const d = layer.drawable(o);
      if (d) ctx.drawImage(sprites.of(o.id, d.raster, d.w, d.h), at.x, at.y, w, h);
      else {
        ctx.fillStyle = '#7a3cff22'; // a picture still decoding
        ctx.fillRect(at.x, at.y, w, h);
      }
    }
    ctx.save();
    ctx.lineWidth = 1;
    if (drawOffBed(ctx, v, o, cols, rows)) {
      // red: it is cut
    } else if (o.kind === 'frame' && o.line === 0) {
      ctx.strokeStyle = ACCENT;
      ctx.setLineDash([6, 4]);
    } else {
      ctx.strokeStyle = '#2b1d4f44';
      ctx.setLineDash([2, 3]);
    }
    // On the box's own outermost pixels, all four sides: two boxes edge to edge show two lines, not one on their shared edge.
    ctx.strokeRect(Math.round(at.x) + 0.5, Math.round(at.y) + 0.5, Math.max(0, Math.round(w) - 1), Math.max(0, Math.round(h) - 1));
    ctx.restore();
  }
  sprites.keepOnly(layer.objects);
  const s = layer.selected;
  if (!s) return;
  ctx.strokeStyle = ACCENT;
  ctx.lineWidth = FRAME_PX;
  const f = selectionFrame(v, s); // outside the box: a line on its edge hid small text's tops and feet
  ctx.strokeRect(f.x, f.y, f.w, f.h);
  ctx.fillStyle = '#fff';
  const half = HANDLE_PX / 2;
  for (const p of handleCentres(v, s)) {
    ctx.fillRect(p.x - half, p.y - half, HANDLE_PX, HANDLE_PX);
    ctx.strokeRect(p.x - half, p.y - half, HANDLE_PX, HANDLE_PX);
  }
}
