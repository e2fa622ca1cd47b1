import { describe, expect, it } from 'vitest';
import { DoseGrid } from '../grid/grid';
import { History } from '../grid/history';
import { line, rectangle } from '../grid/tools';
import { TILE, TileCache } from './tile-cache';
import { fit, panBy, rulerStep, toCell, toScreen, zoomAt } from './viewport';

describe('viewport', () => {
  it('zooms about the pointer and pans by screen pixels', () => {
    const v = { scale: 2, x: 10, y: 20 };
    const z = zoomAt(v, 4, 100, 50);
    expect(toCell(z, 100, 50)).toEqual(toCell(v, 100, 50));
    expect(z.scale).toBe(8);
    const p = panBy(z, 80, -40);
    expect(toScreen(p, 40, 30).x - toScreen(z, 40, 30).x).toBeCloseTo(80);
    expect(zoomAt(v, 1e9, 0, 0).scale).toBe(64);
  });

  it('fits the bed and picks readable ruler steps', () => {
    const f = fit(4096, 2048, 1040, 560);
    expect(f.scale).toBeCloseTo(0.25);
    expect(toScreen(f, 2048, 1024)).toEqual({ x: 520, y: 280 });
    expect(rulerStep(20)).toBe(5);
    expect(rulerStep(3)).toBe(20);
    expect(rulerStep(0.05)).toBe(2000);
  });
});

describe('tile cache', () => {
  it('keeps a one-cell trace visible at every level and remakes only the tiles an edit touched', () => {
    const g = new DoseGrid(4096, 4096);
    let painted = 0;
    const cache = new TileCache(g, (w, h) => ({ w, h, pixels: new Uint32Array(0) as Uint32Array<ArrayBufferLike> }), (t, pixels) => {
      t.pixels = pixels;
      painted++;
    });
    expect(cache.levels.map((l) => l.cols)).toEqual([4096, 2048, 1024, 512, 256]);
    const h = new History(g);
    const e = h.begin('trace');
    line(g, e, 0, 1000, 4095, 1000, 1, 255);
    cache.refresh(0, 1000, 4095, 1000);
    for (let k = 0; k < cache.levels.length; k++) {
      const level = cache.levels[k];
      const y = 1000 >> k;
      expect(level.cells.subarray(y * level.cols, (y + 1) * level.cols).every((v) => v === 255)).toBe(true);
    }
    expect(cache.levelFor(4)).toBe(0);
    expect(cache.levelFor(0.25)).toBe(2);
    expect(cache.levelFor(1 / 64)).toBe(4);
    const t = cache.tile(4, 0, 0);
    expect(t.w).toBe(TILE);
    const before = painted;
    cache.tile(4, 0, 0);
    expect(painted).toBe(before); // clean: not painted again
    const e2 = h.begin('dot');
    e2.set(10, 10, 255);
    cache.refresh(10, 10, 10, 10);
    expect(cache.catchUp(Infinity)).toBe(true);
    cache.tile(4, 0, 0);
    expect(painted).toBe(before + 1);
  });

  it('carries an edit to the coarser levels a band of rows per look at the clock, the levels the same in the end', () => {
    const g = new DoseGrid(4000, 4000);
    const cache = new TileCache(g, () => 0, () => {}, false);
    expect(cache.blank).toBe(true); // made for a blank bed: no tile to draw
    expect(cache.catchUp(0)).toBe(true);
    const whole = new DoseGrid(4000, 4000);
    const h = new History(g);
    rectangle(g, h.begin('fill'), 0, 0, 3999, 3999, true, 1, 200);
    g.cells[3999 * 4000 + 3999] = 255;
    cache.refresh(0, 0, 3999, 3999);
    expect(cache.blank).toBe(false);
    whole.cells.set(g.cells);
    let frames = 1;
    while (!cache.catchUp(0)) frames++; // a deadline already past: one band each time
    expect(frames).toBeGreaterThan(10);
    const levels = cache.levelsSoFar;
    expect(levels[1].cells.every((d, i) => d === (i === levels[1].cells.length - 1 ? 255 : 200))).toBe(true);
    const fresh = new TileCache(whole, () => 0, () => {});
    for (let k = 1; k < levels.length; k++) expect(Buffer.compare(levels[k].cells, fresh.levels[k].cells), `level ${k}`).toBe(0);
  });

  it('holds in each coarser cell the darkest of the four below it, odd sizes and partial edits included', () => {
    let seed = 7;
    const rnd = (n: number) => ((seed = (seed * 1103515245 + 12345) >>> 0) >>> 8) % n;
    const darkest = (src: { cols: number; rows: number; cells: Uint8Array }, x: number, y: number) =>
      Math.max(...[[0, 0], [1, 0], [0, 1], [1, 1]].filter(([dx, dy]) => 2 * x + dx < src.cols && 2 * y + dy < src.rows).map(([dx, dy]) => src.cells[(2 * y + dy) * src.cols + 2 * x + dx]));
    for (const [cols, rows] of [[513, 301], [600, 777], [257, 257]]) {
      const g = new DoseGrid(cols, rows);
      for (let i = 0; i < g.cells.length; i++) g.cells[i] = rnd(256);
      const cache = new TileCache(g, () => 0, () => {});
      for (let n = 0; n < 10; n++) {
        const x0 = rnd(cols), y0 = rnd(rows), x1 = x0 + rnd(40), y1 = y0 + rnd(40);
        for (let y = y0; y <= Math.min(y1, rows - 1); y++) for (let x = x0; x <= Math.min(x1, cols - 1); x++) g.cells[y * cols + x] = rnd(256);
        cache.refresh(x0, y0, x1, y1);
      }
      for (let k = 1; k < cache.levels.length; k++) {
        const src = cache.levels[k - 1], dst = cache.levels[k];
        const wrong = Array.from({ length: dst.rows * dst.cols }, (_, i) => i).filter((i) => dst.cells[i] !== darkest(src, i % dst.cols, Math.floor(i / dst.cols)));
        expect(wrong, `${cols} x ${rows}, level ${k}`).toEqual([]);
      }
    }
  });
});
