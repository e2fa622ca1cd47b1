// The preview's colours: dose from dark to UV violet to white-hot, one colour per LED, and mesh Z.

export const LED_COLOURS: [number, number, number][] = [[123, 47, 247], [194, 24, 91], [21, 101, 192], [0, 137, 123]];

/** 0 → the bed's near-white; up to 1 → deep violet; the share of the job's longest exposure. */
export function doseColour(share: number): [number, number, number] {
  const t = Math.max(0, Math.min(1, share));
  return [Math.round(250 - t * (250 - 60)), Math.round(250 - t * (250 - 10)), Math.round(250 - t * (250 - 140))];
}

/** A colour as one RGBA pixel of an ImageData read as little-endian 32-bit words. */
export function pixelWord([r, g, b]: readonly number[]): number {
  return ((255 << 24) | (b << 16) | (g << 8) | r) >>> 0;
}

/** doseColour as a pixel word, with no array made per pixel: a 512² preview's colours took 47 ms of the page's thread on a busy machine (issue 40). */
export function dosePixel(share: number): number {
  const t = share > 1 ? 1 : share > 0 ? share : 0;
  return ((255 << 24) | (Math.round(250 - t * (250 - 140)) << 16) | (Math.round(250 - t * (250 - 10)) << 8) | Math.round(250 - t * (250 - 60))) >>> 0;
}
