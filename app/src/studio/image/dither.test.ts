import { describe, expect, it } from 'vitest';
import { adjust, NEUTRAL_TONE, toneCurve } from './adjust';
import { HALFTONES, toDoses } from './dither';
import { isLineArt, resample, toGray, type Gray } from './gray';

function ramp(width: number, height: number): Gray {
  const values = new Uint8Array(width * height);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) values[y * width + x] = Math.round((x / (width - 1)) * 255);
  return { width, height, values };
}

function flat(width: number, height: number, v: number): Gray {
  return { width, height, values: new Uint8Array(width * height).fill(v) };
}

const mean = (a: Uint8Array) => a.reduce((s, v) => s + v, 0) / a.length;

describe('image import: grey, size and tone', () => {
  it('lays transparent pixels on white and weighs green most', () => {
    const rgba = new Uint8Array([0, 0, 0, 0, 0, 255, 0, 255, 255, 0, 0, 255, 0, 0, 0, 255]);
    expect(Array.from(toGray(rgba, 4, 1).values)).toEqual([255, 182, 54, 0]);
  });

  it('keeps the overall darkness of a fine pattern when shrinking', () => {
    const checker = { width: 64, height: 64, values: new Uint8Array(64 * 64).map((_, i) => (((i % 64) + Math.floor(i / 64)) % 2 ? 255 : 0)) };
    const small = resample(checker, 16, 16);
    for (const v of small.values) expect(Math.abs(v - 128)).toBeLessThanOrEqual(1);
    expect(resample(flat(3, 3, 40), 7, 5).values.every((v) => v === 40)).toBe(true);
  });

  it('reads a cell\'s grey as the share of it covered, by area: exactly half covered is half dark', () => {
    // Three pixels to two cells: each takes one and a half pixels; the second is a third covered.
    expect(Array.from(resample({ width: 3, height: 1, values: new Uint8Array([0, 0, 255]) }, 2, 1).values)).toEqual([0, 170]);
    expect(255 - resample({ width: 2, height: 1, values: new Uint8Array([0, 255]) }, 1, 1).values[0]).toBe(128); // 127.5 rounds dark
  });

  it('knows line art (black and white, anti-aliased edges) from a photograph', () => {
    const art = { width: 100, height: 1, values: new Uint8Array(100).map((_, i) => (i < 48 ? 0 : i < 51 ? 128 : 255)) };
    expect(isLineArt(art)).toBe(true);
    expect(isLineArt(ramp(100, 4))).toBe(false);
  });

  it('inverts, and contrast and gamma move the mid-tones as they should', () => {
    expect(Array.from(toneCurve(NEUTRAL_TONE)).every((v, i) => v === i)).toBe(true);
    expect(adjust(flat(1, 1, 0), { ...NEUTRAL_TONE, invert: true }).values[0]).toBe(255);
    const lifted = toneCurve({ ...NEUTRAL_TONE, gamma: 2 });
    expect(lifted[128]).toBeGreaterThan(170);
    const hard = toneCurve({ ...NEUTRAL_TONE, contrast: 100 });
    expect(hard[100]).toBe(0);
    expect(hard[160]).toBe(255);
    const soft = toneCurve({ ...NEUTRAL_TONE, contrast: -50 });
    expect(soft[0]).toBeGreaterThan(40);
    expect(soft[255]).toBeLessThan(215);
  });
});

describe('image import: from grey to doses', () => {
  it('semitones keep every level, darker is more dose', () => {
    expect(Array.from(toDoses(ramp(5, 1), 'semitones'))).toEqual([255, 191, 127, 64, 0]);
  });

  it('a threshold exposes what is darker than its level', () => {
    // darkness 255, 128, 127, 0 against a level of 128
    const d = toDoses({ width: 4, height: 1, values: new Uint8Array([0, 127, 128, 255]) }, 'threshold', 128);
    expect(Array.from(d)).toEqual([255, 255, 0, 0]);
  });

  for (const h of HALFTONES.filter((h) => h !== 'semitones' && h !== 'threshold')) {
    it(`${h} gives only 0 and 255 and keeps each grey's darkness`, () => {
      for (const grey of [32, 96, 160, 224]) {
        const d = toDoses(flat(64, 64, grey), h);
        expect(d.every((v) => v === 0 || v === 255)).toBe(true);
        // Atkinson drops a quarter of each error on purpose, so near-white and near-black drift.
        const tolerance = h === 'atkinson' && (grey < 64 || grey > 192) ? 36 : h === 'atkinson' ? 12 : 6;
        expect(Math.abs(mean(d) - (255 - grey))).toBeLessThan(tolerance);
      }
      // A ramp's darkness falls from left to right.
      const d = toDoses(ramp(256, 32), h);
      const column = (x0: number) => {
        let s = 0;
        for (let y = 0; y < 32; y++) for (let x = x0; x < x0 + 32; x++) s += d[y * 256 + x];
        return s / (32 * 32);
      };
      expect(column(0)).toBeGreaterThan(column(112));
      expect(column(112)).toBeGreaterThan(column(224));
      // Pure black and pure white stay solid.
      expect(toDoses(flat(16, 16, 0), h).every((v) => v === 255)).toBe(true);
      expect(toDoses(flat(16, 16, 255), h).every((v) => v === 0)).toBe(true);
    });
  }

  it('ordered dither is the 8 × 8 Bayer pattern: a 50 % grey lights exactly half of each tile', () => {
    const d = toDoses(flat(8, 8, 127), 'ordered');
    expect(d.filter((v) => v === 255).length).toBe(32);
  });
});
