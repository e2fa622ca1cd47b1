// Tone adjustments of an imported picture before it becomes doses: invert, contrast and gamma.

import type { Gray } from './gray';

export interface Tone {
  /** Swap black and white (a negative resist, or a picture drawn white on black). */
  invert: boolean;
  /** -100 … 100: 0 keeps the picture, 100 pushes every grey to black or white. */
  contrast: number;
  /** > 0: 1 keeps the picture; above 1 lightens the mid-tones, below darkens them. */
  gamma: number;
}

export const NEUTRAL_TONE: Tone = { invert: false, contrast: 0, gamma: 1 };

/** A 256-entry table for the tone: every pixel maps through it. */
export function toneCurve(t: Tone): Uint8Array {
  const lut = new Uint8Array(256);
  const k = Math.tan(((Math.max(-100, Math.min(100, t.contrast)) + 100) / 200) * (Math.PI / 2) * 0.999);
  const gamma = t.gamma > 0 ? t.gamma : 1;
  for (let v = 0; v < 256; v++) {
    let x = v / 255;
    x = Math.pow(x, 1 / gamma);
    x = (x - 0.5) * k + 0.5;
    x = Math.max(0, Math.min(1, x));
    if (t.invert) x = 1 - x;
    lut[v] = Math.round(x * 255);
  }
  return lut;
}

export function adjust(src: Gray, t: Tone): Gray {
  const lut = toneCurve(t);
  const values = new Uint8Array(src.values.length);
  for (let i = 0; i < values.length; i++) values[i] = lut[src.values[i]];
  return { width: src.width, height: src.height, values };
}
