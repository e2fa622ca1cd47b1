// A raster's sprite, as the editor draws it: made here on the page, or off the page's thread by the
// work worker for a large raster (kept in objects/raster.ts `madeSprites`).
import type { Raster } from '../objects/raster';

/** A raster's sprite pixels, RGBA as one 32-bit word each through the dose colours: dose 0 see-through. */
export function spritePixels(raster: Raster, lut: Uint32Array): Uint32Array<ArrayBuffer> {
  const pixels = new Uint32Array(raster.length);
  for (let i = 0; i < raster.length; i++) if (raster[i]) pixels[i] = lut[raster[i]];
  return pixels;
}
