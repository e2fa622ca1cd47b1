// From grey to doses: a cell's dose is how dark it is (black = 255, full exposure; white = 0).
// Semitones keep every level; a threshold or a dither gives only 0 and 255, for resists that
// don't take partial exposure well.

import type { Gray } from './gray';
import type { Halftone } from './halftones';

export { HALFTONES, type Halftone } from './halftones';

/** Error-diffusion kernels: [dx, dy, weight], with their divisor. */
const KERNELS: Record<'floyd-steinberg' | 'atkinson' | 'jarvis' | 'stucki', { divisor: number; taps: [number, number, number][] }> = {
  'floyd-steinberg': { divisor: 16, taps: [[1, 0, 7], [-1, 1, 3], [0, 1, 5], [1, 1, 1]] },
  // Atkinson spreads only 6/8 of the error: highlights and shadows stay clean.
  atkinson: { divisor: 8, taps: [[1, 0, 1], [2, 0, 1], [-1, 1, 1], [0, 1, 1], [1, 1, 1], [0, 2, 1]] },
  jarvis: {
    divisor: 48,
    taps: [[1, 0, 7], [2, 0, 5], [-2, 1, 3], [-1, 1, 5], [0, 1, 7], [1, 1, 5], [2, 1, 3], [-2, 2, 1], [-1, 2, 3], [0, 2, 5], [1, 2, 3], [2, 2, 1]],
  },
  stucki: {
    divisor: 42,
    taps: [[1, 0, 8], [2, 0, 4], [-2, 1, 2], [-1, 1, 4], [0, 1, 8], [1, 1, 4], [2, 1, 2], [-2, 2, 1], [-1, 2, 2], [0, 2, 4], [1, 2, 2], [2, 2, 1]],
  },
};

/** The 8 × 8 Bayer matrix, 0 … 63. */
const BAYER8 = (() => {
  const m = new Uint8Array(64);
  for (let y = 0; y < 8; y++)
    for (let x = 0; x < 8; x++) {
      let v = 0;
      for (let bit = 0, xx = x, yy = x ^ y; bit < 3; bit++, xx >>= 1, yy >>= 1) v |= (((yy & 1) << 1) | (xx & 1)) << (2 * (2 - bit));
      m[y * 8 + x] = v;
    }
  return m;
})();

/**
 * Doses for a grey picture. `level` is the threshold's cut-off in darkness (a cell darker than it
 * is exposed). Error diffusion runs serpentine (every other row right to left), which avoids the
 * diagonal "worms" a one-way scan leaves in flat areas.
 */
export function toDoses(src: Gray, halftone: Halftone, level = 128): Uint8Array {
  const n = src.width * src.height;
  const out = new Uint8Array(n);
  if (halftone === 'semitones') {
    for (let i = 0; i < n; i++) out[i] = 255 - src.values[i];
    return out;
  }
  if (halftone === 'threshold') {
    for (let i = 0; i < n; i++) out[i] = 255 - src.values[i] >= level ? 255 : 0;
    return out;
  }
  if (halftone === 'ordered') {
    for (let y = 0; y < src.height; y++)
      for (let x = 0; x < src.width; x++) {
        const i = y * src.width + x;
        const dark = 255 - src.values[i];
        out[i] = dark * 64 > (BAYER8[(y & 7) * 8 + (x & 7)] + 0.5) * 255 ? 255 : 0;
      }
    return out;
  }
  const { divisor, taps } = KERNELS[halftone];
  const w = src.width, h = src.height;
  const dark = new Float32Array(n);
  for (let i = 0; i < n; i++) dark[i] = 255 - src.values[i];
  for (let y = 0; y < h; y++) {
    const reverse = (y & 1) === 1;
    for (let k = 0; k < w; k++) {
      const x = reverse ? w - 1 - k : k;
      const i = y * w + x;
      const v = dark[i] >= 128 ? 255 : 0;
      out[i] = v;
      const err = dark[i] - v;
      for (const [dx, dy, weight] of taps) {
        const tx = x + (reverse ? -dx : dx), ty = y + dy;
        if (tx < 0 || tx >= w || ty >= h) continue;
        dark[ty * w + tx] += (err * weight) / divisor;
      }
    }
  }
  return out;
}
