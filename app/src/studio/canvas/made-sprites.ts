// Sprites made off the page's thread (the work worker draws a large raster's as an ImageBitmap),
// known by the raster they show; the editor draws them instead of making its own.
import type { Raster } from '../objects/raster';

export const madeSprites = new WeakMap<Raster, CanvasImageSource>();

/** A raster's sprite pixels, RGBA as one 32-bit word each through the dose colours: dose 0 see-through. */
export function spritePixels(raster: Raster, lut: Uint32Array): Uint32Array<ArrayBuffer> {
  const pixels = new Uint32Array(raster.length);
  for (let i = 0; i < raster.length; i++) if (raster[i]) pixels[i] = lut[raster[i]];
  return pixels;
}
