// The width rule of protocol/artwork.md, checked on traces and pads at many positions against the grid.
import { describe, expect, it } from 'vitest';
import { rasteriseBoard, TIE_NUDGE_MM } from './rasterise';
import { at, boardOf, gerber } from './test-boards';

const P = 0.05; // 50 µm cells

/** Exposed cells across the middle of the picture: along a row (across a vertical feature) or down a column. */
function widthInCells(text: string, across: 'x' | 'y', threshold: number): number {
  const set = boardOf(gerber(text));
  const r = rasteriseBoard(set, { expose: ['other'], pitchUm: { x: 50, y: 50 }, threshold, windowMm: { x0: 0, y0: 0, x1: 3, y1: 3 } });
  let n = 0;
  for (let i = 0; i < 60; i++) n += across === 'x' ? r.cells[30 * 60 + i] : r.cells[i * 60 + 30];
  return n;
}

const verticalTrace = (x: number, w: number) => `%ADD10C,${w}*%\nD10*\n${at(x, 0.5)}D02*\n${at(x, 2.5)}D01*`;
const horizontalTrace = (y: number, w: number) => `%ADD10C,${w}*%\nD10*\n${at(0.5, y)}D02*\n${at(2.5, y)}D01*`;
const pad = (x: number, y: number, w: number, h: number) => `%ADD10R,${w}X${h}*%\nD10*\n${at(x, y)}D03*`;

/**
 * The rule, in closed form: a feature from a to b (b − a ≥ one cell) exposes the cells [k·p, (k+1)·p) with
 * (k+1)·p − a ≥ t·p and b − k·p ≥ t·p, i.e. k from ⌈a/p + t − 1⌉ to ⌊b/p − t⌋. Ties are settled as if the
 * artwork lay TIE_NUDGE_MM towards −x and +y.
 */
function cellsByRule(a: number, b: number, t: number, axis: 'x' | 'y' = 'x'): number {
  const shift = axis === 'x' ? -TIE_NUDGE_MM : TIE_NUDGE_MM;
  const lo = Math.ceil((a + shift) / P + t - 1 - 1e-9);
  const hi = Math.floor((b + shift) / P - t + 1e-9);
  return hi - lo + 1;
}

// Offsets of a feature's near edge past a cell boundary, in µm: on the boundary, on the centre, and between.
const OFFSETS_UM = [0, 1, 5, 10, 12.5, 20, 24, 25, 26, 30, 37.5, 45, 49, 49.9];

describe('a feature’s width in cells at a 50 % threshold', () => {
  it('makes a 0.2 mm trace 4 cells wide at 50 µm, wherever it lies on the grid, along either axis', () => {
    for (const off of OFFSETS_UM) {
      const edge = 1 + off / 1000; // near edge; the centre is 0.1 mm further on
      expect(widthInCells(verticalTrace(edge + 0.1, 0.2), 'x', 0.5), `vertical trace, edge ${off} µm past a boundary`).toBe(4);
      expect(widthInCells(horizontalTrace(edge + 0.1, 0.2), 'y', 0.5), `horizontal trace, edge ${off} µm past a boundary`).toBe(4);
      expect(widthInCells(pad(edge + 0.1, 1.5, 0.2, 1), 'x', 0.5), `pad, ${off} µm`).toBe(4);
      expect(widthInCells(pad(1.5, edge + 0.1, 1, 0.2), 'y', 0.5), `pad, ${off} µm`).toBe(4);
    }
  }, 60_000);

  it('makes a width of n whole cells n cells, and any other width the cells whose centres it covers', () => {
    for (const w of [0.1, 0.15, 0.175, 0.25, 0.3, 0.33]) {
      for (const off of OFFSETS_UM) {
        const a = 1 + off / 1000;
        for (const axis of ['x', 'y'] as const) {
          const expected = cellsByRule(a, a + w, 0.5, axis);
          if (Math.abs(w / P - Math.round(w / P)) < 1e-9) expect(expected).toBe(Math.round(w / P));
          else expect([Math.floor(w / P), Math.ceil(w / P)]).toContain(expected);
          const trace = axis === 'x' ? verticalTrace(a + w / 2, w) : horizontalTrace(a + w / 2, w);
          expect(widthInCells(trace, axis, 0.5), `${w} mm at ${off} µm along ${axis}`).toBe(expected);
        }
      }
    }
  }, 60_000); // many boards, on a shared machine
});

describe('a feature’s width in cells at other thresholds', () => {
  it('widens a feature by (1 − 2t) of a cell on average across the scan: exact by the rule', () => {
    for (const t of [0.2, 0.3, 0.7, 0.8]) {
      for (const w of [0.15, 0.2, 0.225]) {
        for (const off of OFFSETS_UM) {
          const a = 1 + off / 1000;
          expect(widthInCells(verticalTrace(a + w / 2, w), 'x', t), `t ${t}, ${w} mm at ${off} µm`).toBe(cellsByRule(a, a + w, t));
        }
      }
    }
  }, 60_000);

  it('keeps within one cell of the rule down the scan, where coverage is sampled on 15 lines', () => {
    for (const t of [0.2, 0.3, 0.7, 0.8]) {
      for (const off of OFFSETS_UM) {
        const a = 1 + off / 1000;
        const n = widthInCells(horizontalTrace(a + 0.1, 0.2), 'y', t);
        expect(Math.abs(n - cellsByRule(a, a + 0.2, t, 'y')), `t ${t} at ${off} µm`).toBeLessThanOrEqual(1);
      }
    }
  }, 60_000); // many boards, on a shared machine
});
