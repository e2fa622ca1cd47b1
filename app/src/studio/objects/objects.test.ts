import { describe, expect, it } from 'vitest';
import { DoseGrid } from '../grid/grid';
import { NEUTRAL_TONE } from '../image/adjust';
import { centredAt, exposes, moved, objectAt, resized, type FrameObject, type ImageObject, type StudioObject, type TextObject } from './objects';
import { compose, composeSoon, frameRaster, layOver, rasterOf, type Polarity, type RasterSources } from './raster';
import { bitmapArtwork, cutOf, ready } from './artwork';
import type { Gray } from '../image/gray';
import { cssFont, linesOf } from './text-raster';

const frame = (over: Partial<FrameObject> = {}): FrameObject => ({ kind: 'frame', id: 1, x: 2, y: 3, w: 5, h: 4, line: 1, dose: 200, ...over });
const picture = (over: Partial<ImageObject> = {}): ImageObject => ({
  kind: 'image', id: 2, x: 0, y: 0, w: 4, h: 2, name: 'p.png', src: 'data:p', halftone: 'semitones', threshold: 50, tone: { ...NEUTRAL_TONE }, ...over,
});

describe('objects', () => {
  it('finds the topmost object under a cell, and none outside every box', () => {
    const a = picture({ id: 1, x: 0, y: 0, w: 10, h: 10 }), b = picture({ id: 2, x: 5, y: 5, w: 10, h: 10 });
    expect(objectAt([a, b], 6, 6)?.id).toBe(2);
    expect(objectAt([a, b], 2, 2)?.id).toBe(1);
    expect(objectAt([a, b], 15, 15)).toBeNull(); // the box's far edge is outside it
  });

  it('hits a frame on its border only, so what it frames can be picked', () => {
    const pic = picture({ id: 5, x: 10, y: 10, w: 10, h: 10 });
    const f = frame({ id: 6, x: 0, y: 0, w: 40, h: 40, line: 0 });
    expect(objectAt([pic, f], 15, 15, 2)?.id).toBe(5);
    expect(objectAt([pic, f], 39, 20, 2)?.id).toBe(6);
    expect(objectAt([pic, f], 41, 20, 2)?.id).toBe(6); // just outside, within the pointer's reach
    expect(objectAt([pic, f], 30, 30, 2)).toBeNull();
  });

  it('resizes from a corner with the opposite corner fixed', () => {
    expect(resized({ x: 10, y: 10, w: 20, h: 10 }, 'se', { x: 40, y: 30 }, false)).toEqual({ x: 10, y: 10, w: 30, h: 20 });
    expect(resized({ x: 10, y: 10, w: 20, h: 10 }, 'nw', { x: 0, y: 5 }, false)).toEqual({ x: 0, y: 5, w: 30, h: 15 });
  });

  it('keeps a picture\'s proportions, following the side dragged further', () => {
    expect(resized({ x: 10, y: 10, w: 20, h: 10 }, 'se', { x: 50, y: 12 }, true)).toEqual({ x: 10, y: 10, w: 40, h: 20 });
    expect(resized({ x: 10, y: 10, w: 20, h: 10 }, 'ne', { x: 12, y: 0 }, true)).toEqual({ x: 10, y: 0, w: 40, h: 20 });
  });

  it('never resizes to nothing, even dragged past the opposite corner', () => {
    const r = resized({ x: 10, y: 10, w: 20, h: 10 }, 'se', { x: 10, y: 10 }, false);
    expect(r.w).toBeGreaterThanOrEqual(1);
    expect(r.h).toBeGreaterThanOrEqual(1);
  });

  it('moves by whole cells and keeps part of the box on the bed', () => {
    expect(moved({ x: 5, y: 5, w: 10, h: 10 }, 2.4, -1.6, 100, 100)).toEqual({ x: 7, y: 3, w: 10, h: 10 });
    expect(moved({ x: 5, y: 5, w: 10, h: 10 }, -500, 500, 100, 100)).toEqual({ x: -9, y: 99, w: 10, h: 10 });
  });

  it('centres a new box where the view is, on the bed', () => {
    expect(centredAt(50, 50, 10, 20, 100, 100)).toEqual({ x: 45, y: 40, w: 10, h: 20 });
    expect(centredAt(2, 98, 10, 20, 100, 100)).toEqual({ x: 0, y: 80, w: 10, h: 20 });
  });

  it('knows a guide frame and empty text expose nothing', () => {
    expect(exposes(frame({ line: 0 }))).toBe(false);
    expect(exposes(frame())).toBe(true);
    const text: TextObject = { kind: 'text', id: 3, x: 0, y: 0, w: 5, h: 5, text: '  ', font: 'serif', bold: false, dose: 255 };
    expect(exposes(text)).toBe(false);
    expect(exposes({ ...text, text: 'A' })).toBe(true);
  });
});

describe('rasters', () => {
  it('draws a frame as an outline of its line width', () => {
    const r = frameRaster(frame({ w: 5, h: 4, line: 1, dose: 9 }));
    expect(Array.from(r)).toEqual([9, 9, 9, 9, 9, 9, 0, 0, 0, 9, 9, 0, 0, 0, 9, 9, 9, 9, 9, 9]);
    expect(Array.from(frameRaster(frame({ w: 3, h: 3, line: 5, dose: 1 })))).toEqual(Array(9).fill(1)); // too thick: solid
  });

  /** A picture's rasters through the artwork it is read as. */
  const sources = (gray: Gray): RasterSources => ({ artwork: () => ready(bitmapArtwork(gray)), text: () => new Uint8Array() });
  const raster = (o: StudioObject, gray: Gray, polarity: Polarity = 'negative') => Array.from(rasterOf(o, sources(gray), polarity)!);

  it('turns a picture into doses at its box size: black is the full dose', () => {
    const gray = { width: 2, height: 1, values: new Uint8Array([0, 255]) };
    expect(raster(picture({ w: 4, h: 2 }), gray)).toEqual([255, 255, 0, 0, 255, 255, 0, 0]);
    expect(raster(picture({ w: 2, h: 1, tone: { ...NEUTRAL_TONE, invert: true } }), gray)).toEqual([0, 255]);
  });

  it('exposes a cell by coverage: when the artwork covers at least the threshold\'s share of it', () => {
    // Four pixels to one cell: three of them black covers 75 % of it; two, exactly half.
    const threeQuarters = { width: 4, height: 1, values: new Uint8Array([0, 0, 0, 255]) };
    const half = { width: 4, height: 1, values: new Uint8Array([0, 0, 255, 255]) };
    const cell = (threshold: number, gray: Gray) => raster(picture({ w: 1, h: 1, halftone: 'threshold', threshold }), gray)[0];
    expect([cell(50, threeQuarters), cell(75, threeQuarters), cell(76, threeQuarters)]).toEqual([255, 255, 0]);
    expect([cell(50, half), cell(51, half)]).toEqual([255, 0]);
    // Version 1's level in 255ths is the same cut as its share in percent.
    for (let level = 1; level <= 255; level++) expect(cutOf((level * 100) / 255)).toBe(level);
  });

  it('turns and mirrors any kind alike: the upright raster moved onto the box', () => {
    // A 3 × 2 picture, black only at its top-left pixel.
    const corner = { width: 3, height: 2, values: new Uint8Array([0, 255, 255, 255, 255, 255]) };
    expect(raster(picture({ w: 2, h: 3, turn: 1 }), corner)).toEqual([0, 255, 0, 0, 0, 0]); // top-right on the bed
    expect(raster(picture({ w: 3, h: 2, mirror: true }), corner)).toEqual([0, 0, 255, 0, 0, 0]);
    expect(raster(picture({ w: 3, h: 2, turn: 2, mirror: true }), corner)).toEqual([0, 0, 0, 255, 0, 0]);
    expect(Array.from(rasterOf(frame({ w: 2, h: 4, line: 1, dose: 9, turn: 1 }), sources(corner))!)).toEqual(Array(8).fill(9));
  });

  it('with positive resist exposes what the artwork does not cover, at each object\'s own dose', () => {
    const gray = { width: 2, height: 1, values: new Uint8Array([0, 255]) };
    expect(raster(picture({ w: 2, h: 1 }), gray, 'positive')).toEqual([0, 255]);
    expect(Array.from(rasterOf(frame({ w: 3, h: 3, line: 1, dose: 200 }), sources(gray), 'positive')!)).toEqual([0, 0, 0, 0, 200, 0, 0, 0, 0]);
  });

  it('with positive resist, copper drawn by any object keeps its resist where objects overlap', () => {
    const paint = new DoseGrid(6, 1);
    paint.cells[5] = 80;
    // Two boxes overlapping on cells 2 and 3; the first has copper at cell 2, the second at cell 3.
    const a = picture({ id: 1, x: 0, y: 0, w: 4, h: 1 }), b = picture({ id: 2, x: 2, y: 0, w: 3, h: 1 });
    const exposure = (o: StudioObject) => new Uint8Array(o.id === 1 ? [255, 255, 0, 255] : [255, 0, 255]);
    expect(Array.from(compose(paint, [a, b], exposure, 'positive').cells)).toEqual([255, 255, 0, 0, 255, 80]);
    expect(Array.from(compose(paint, [a, b], exposure, 'negative').cells)).toEqual([255, 255, 255, 255, 255, 80]);
  });

  it('composes the same in steps, letting the page run after the copy and after each band of an object\'s rows', async () => {
    const paint = new DoseGrid(6, 1);
    paint.cells[5] = 80;
    const a = picture({ id: 1, x: 0, y: 0, w: 4, h: 1 }), b = picture({ id: 2, x: 2, y: 0, w: 3, h: 1 });
    const exposure = (o: StudioObject) => new Uint8Array(o.id === 1 ? [255, 255, 0, 255] : [255, 0, 255]);
    for (const polarity of ['positive', 'negative'] as const) {
      let pauses = 0;
      const soon = await composeSoon(paint, [a, b], exposure, polarity, async () => pauses++);
      expect(Array.from(soon.cells), polarity).toEqual(Array.from(compose(paint, [a, b], exposure, polarity).cells));
      expect(pauses, polarity).toBe(polarity === 'negative' ? 5 : 6); // the copy, each object and its one band; the positive's last merge
    }
    expect(await composeSoon(paint, [], exposure, 'negative', async () => {})).toBe(paint);
    // A board of 1500 × 1600 cells laid in bands of about a million cells each, partly off a bed of 2000 × 1500
    const bed = new DoseGrid(2000, 1500);
    bed.cells.fill(30, 0, 2000 * 10);
    const board = picture({ id: 3, x: 700, y: -50, w: 1500, h: 1600 });
    const cells = new Uint8Array(1500 * 1600).map((_, i) => (i * 7919) % 251);
    for (const polarity of ['positive', 'negative'] as const) {
      let pauses = 0;
      const soon = await composeSoon(bed, [board], () => cells, polarity, async () => pauses++);
      expect(Buffer.compare(soon.cells, compose(bed, [board], () => cells, polarity).cells), polarity).toBe(0);
      expect(pauses, polarity).toBeGreaterThanOrEqual(polarity === 'negative' ? 3 : 6);
      if (polarity === 'negative') {
        let wrong = 0;
        for (let y = 0; y < 1500; y++)
          for (let x = 0; x < 2000; x++) {
            const under = x >= 700 ? cells[(y + 50) * 1500 + x - 700] : 0;
            if (soon.cells[y * 2000 + x] !== Math.max(bed.cells[y * 2000 + x], under)) wrong++;
          }
        expect(wrong).toBe(0);
      }
    }
  });

  it('composes objects over the painted cells: the greater dose wins, the bed clips', () => {
    const paint = new DoseGrid(6, 6);
    paint.cells[0] = 100;
    paint.cells[7] = 250;
    const objects: StudioObject[] = [frame({ x: -1, y: -1, w: 3, h: 3, line: 1, dose: 200 }), frame({ id: 9, x: 0, y: 0, w: 6, h: 6, line: 0 })];
    const out = compose(paint, objects, (o) => (o.kind === 'frame' ? frameRaster(o) : null));
    expect(out).not.toBe(paint);
    expect(paint.cells[0]).toBe(100); // the painting is not touched
    expect(out.cells[0]).toBe(100); // the frame's hollow centre lies on cell (0, 0)
    expect(out.cells[1]).toBe(200);
    expect(out.cells[6]).toBe(200);
    expect(out.cells[7]).toBe(250);
    expect(out.cells[2]).toBe(0);
  });

  it('lays a raster over the cells it covers on the grid, and says which', () => {
    const g = new DoseGrid(4, 4);
    g.cells[5] = 200;
    expect(layOver(g, { x: 1, y: 1, w: 5, h: 1 }, new Uint8Array(5).fill(100))).toEqual({ x0: 1, y0: 1, x1: 3, y1: 1 });
    expect(Array.from(g.cells.subarray(4, 8))).toEqual([0, 200, 100, 100]);
    expect(layOver(g, { x: 4, y: 0, w: 2, h: 2 }, new Uint8Array(4).fill(9))).toBeNull(); // beside the grid
  });

  it('gives back the painting itself when no object exposes anything', () => {
    const paint = new DoseGrid(4, 4);
    expect(compose(paint, [frame({ line: 0 })], () => null)).toBe(paint);
  });
});

describe('text', () => {
  it('quotes a named family and keeps a generic one bare', () => {
    expect(cssFont({ font: 'DejaVu Sans', bold: true }, 12)).toBe('bold 12px "DejaVu Sans", sans-serif');
    expect(cssFont({ font: 'monospace', bold: false }, 8)).toBe('8px monospace');
    expect(cssFont({ font: 'Evil"; x', bold: false }, 8)).toBe('8px "Evil; x", sans-serif');
  });

  it('splits lines on either line ending', () => {
    expect(linesOf('a\r\nb\nc')).toEqual(['a', 'b', 'c']);
  });
});
