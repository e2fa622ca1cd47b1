import { describe, expect, it } from 'vitest';
import { cellsAt, densityOf, shownDpi, type Density } from './density';
import { bmpFile, halfBlack, jpegFile, pngFile } from './picture-files.fixture';

const PITCH = { x: 50, y: 50 };
/** 600 and 300 dpi as a PNG or BMP states them: whole pixels per metre. */
const PPM_600 = 23622, PPM_300 = 11811;

/** Within half a cell of the size the header states, on both axes. */
function expectTrueSize(bytes: Uint8Array, px: { width: number; height: number }, trueMm: { x: number; y: number }) {
  const dpi = densityOf(bytes)!;
  expect(dpi).not.toBeNull();
  const { w, h } = cellsAt(px, dpi, PITCH);
  expect(Math.abs((w * PITCH.x) / 1000 - trueMm.x)).toBeLessThanOrEqual(PITCH.x / 2000);
  expect(Math.abs((h * PITCH.y) / 1000 - trueMm.y)).toBeLessThanOrEqual(PITCH.y / 2000);
}

describe('the resolution a picture file states', () => {
  it('PNG: pHYs in pixels per metre; none, or an aspect only, is no resolution', () => {
    const png = pngFile(709, 472, halfBlack(709), { pixelsPerMetre: { x: PPM_600, y: PPM_600 } });
    expect(densityOf(png)!.x).toBeCloseTo(600, 2);
    // A 30 × 20 mm board exported at 600 dpi lands 30 × 20 mm, not 40 mm wide.
    expectTrueSize(png, { width: 709, height: 472 }, { x: (709 / PPM_600) * 1000, y: (472 / PPM_600) * 1000 });
    expect(densityOf(pngFile(8, 8, halfBlack(8)))).toBeNull();
    expect(densityOf(pngFile(8, 8, halfBlack(8), { pixelsPerMetre: { x: 2, y: 1 }, aspectOnly: true }))).toBeNull();
    const unequal = densityOf(pngFile(8, 8, halfBlack(8), { pixelsPerMetre: { x: PPM_600, y: PPM_300 } }))!;
    expect([Math.round(unequal.x), Math.round(unequal.y)]).toEqual([600, 300]);
  });

  it('JPEG: JFIF per inch or per cm, else EXIF in either byte order', () => {
    const jfif = jpegFile(472, 236, halfBlack(472), { jfif: { units: 1, x: 600, y: 600 } });
    expect(densityOf(jfif)).toEqual({ x: 600, y: 600 });
    expectTrueSize(jfif, { width: 472, height: 236 }, { x: (472 / 600) * 25.4, y: (236 / 600) * 25.4 });
    expect(densityOf(jpegFile(16, 16, halfBlack(16), { jfif: { units: 2, x: 118, y: 118 } }))!.x).toBeCloseTo(299.72, 2);
    // Units 0 is an aspect ratio: no resolution, unless EXIF states one.
    expect(densityOf(jpegFile(16, 16, halfBlack(16), { jfif: { units: 0, x: 1, y: 1 } }))).toBeNull();
    const exif = jpegFile(300, 150, halfBlack(300), { jfif: { units: 0, x: 1, y: 1 }, exif: { unit: 2, x: [300, 1], y: [300, 1] } });
    expect(densityOf(exif)).toEqual({ x: 300, y: 300 });
    expectTrueSize(exif, { width: 300, height: 150 }, { x: 25.4, y: 12.7 });
    expect(densityOf(jpegFile(16, 16, halfBlack(16), { exif: { unit: 3, x: [2362, 20], y: [2362, 20], littleEndian: true } }))!.x).toBeCloseTo(299.97, 2);
    expect(densityOf(jpegFile(16, 16, halfBlack(16), { exif: { unit: 1, x: [72, 1], y: [72, 1] } }))).toBeNull();
    expect(densityOf(jpegFile(16, 16, halfBlack(16)))).toBeNull();
  });

  it('BMP: pixels per metre; 0 is none', () => {
    const bmp = bmpFile(354, 236, halfBlack(354), { x: PPM_300, y: PPM_300 });
    expect(densityOf(bmp)!.x).toBeCloseTo(300, 2);
    expectTrueSize(bmp, { width: 354, height: 236 }, { x: (354 / PPM_300) * 1000, y: (236 / PPM_300) * 1000 });
    expect(densityOf(bmpFile(4, 4, halfBlack(4)))).toBeNull();
  });

  it('says nothing of other files, and never throws on a cut or damaged header', () => {
    expect(densityOf(new TextEncoder().encode('GIF89a'))).toBeNull();
    expect(densityOf(new Uint8Array())).toBeNull();
    const files = [
      pngFile(8, 8, halfBlack(8), { pixelsPerMetre: { x: PPM_600, y: PPM_600 } }),
      jpegFile(16, 16, halfBlack(16), { jfif: { units: 0, x: 1, y: 1 }, exif: { unit: 2, x: [300, 1], y: [300, 1] } }),
      bmpFile(4, 4, halfBlack(4), { x: PPM_300, y: PPM_300 }),
    ];
    for (const f of files)
      for (let n = 0; n < Math.min(f.length, 200); n++) {
        const cut = f.slice(0, n);
        const d: Density | null = densityOf(cut);
        if (d) expect(d.x > 0 && d.y > 0).toBe(true);
        const damaged = f.slice();
        damaged[n] ^= 0xff;
        expect(() => densityOf(damaged)).not.toThrow();
      }
  });
});

describe('the resolution shown for a picture on the bed (issue 29, item 14)', () => {
  it('a 600-dpi PNG reads 600 DPI, not 600.3', () => {
    const dpi = densityOf(pngFile(709, 472, halfBlack(709), { pixelsPerMetre: { x: PPM_600, y: PPM_600 } }))!;
    const { w } = cellsAt({ width: 709, height: 472 }, dpi, PITCH);
    expect((709 * 25400) / (w * PITCH.x)).not.toBe(600); // the width in whole cells is not exactly 600 dpi
    expect(shownDpi(709, w, PITCH.x)).toBe(600);
  });
  it('is the roundest resolution that gives the same cells, and gives them', () => {
    for (const [px, dpi, pitch] of [[709, 600, 50], [1000, 300, 50], [123, 72, 50], [4000, 1200, 25], [709, 601, 50], [50, 96, 100]]) {
      const { w } = cellsAt({ width: px, height: 1 }, { x: dpi, y: dpi }, { x: pitch, y: pitch });
      const shown = shownDpi(px, w, pitch);
      expect(cellsAt({ width: px, height: 1 }, { x: shown, y: shown }, { x: pitch, y: pitch }).w, `${px} px at ${dpi}`).toBe(w);
      expect(Number.isInteger(shown), `${px} px at ${dpi}: ${shown}`).toBe(true);
    }
    // A picture stretched by hand shows what it is, with decimals where a whole number gives other cells.
    expect(shownDpi(10, 2000, 50)).toBe(2.54);
  });
});
