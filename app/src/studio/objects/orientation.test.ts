import { describe, expect, it } from 'vitest';
import type { Turn } from './objects';
import { boxSize, frameSize, mirrored, orient, orientationLabel, turned } from './orientation';

/** A 3 × 2 frame with every cell different: 1 2 3 / 4 5 6. */
const CELLS = new Uint8Array([1, 2, 3, 4, 5, 6]);
const rows = (cells: Uint8Array, w: number) => Array.from({ length: cells.length / w }, (_, y) => Array.from(cells.subarray(y * w, y * w + w)));

/** The bed's cells flipped as they lie: what a mirror on the bed must give. */
function flip(cells: Uint8Array, w: number, h: number, axis: 'x' | 'y'): Uint8Array {
  const out = new Uint8Array(cells.length);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) out[y * w + x] = axis === 'x' ? cells[y * w + (w - 1 - x)] : cells[(h - 1 - y) * w + x];
  return out;
}

describe('turning and mirroring', () => {
  it('turns the cells clockwise a quarter at a time, after the mirror', () => {
    expect(rows(orient(CELLS, 3, 2, {}), 3)).toEqual([[1, 2, 3], [4, 5, 6]]);
    expect(orient(CELLS, 3, 2, { turn: 0, mirror: false })).toBe(CELLS); // nothing to do: the same cells
    expect(rows(orient(CELLS, 3, 2, { turn: 1 }), 2)).toEqual([[4, 1], [5, 2], [6, 3]]);
    expect(rows(orient(CELLS, 3, 2, { turn: 2 }), 3)).toEqual([[6, 5, 4], [3, 2, 1]]);
    expect(rows(orient(CELLS, 3, 2, { turn: 3 }), 2)).toEqual([[3, 6], [2, 5], [1, 4]]);
    expect(rows(orient(CELLS, 3, 2, { mirror: true }), 3)).toEqual([[3, 2, 1], [6, 5, 4]]);
    expect(rows(orient(CELLS, 3, 2, { mirror: true, turn: 1 }), 2)).toEqual([[6, 3], [5, 2], [4, 1]]);
  });

  it('mirrors across the bed\'s X or Y as the object lies, whatever its turn', () => {
    for (const turn of [0, 1, 2, 3] as Turn[])
      for (const mirror of [false, true])
        for (const axis of ['x', 'y'] as const) {
          const before = { turn, mirror };
          const { w, h } = boxSize(before, 3, 2);
          const expected = flip(orient(CELLS, 3, 2, before), w, h, axis);
          expect(orient(CELLS, 3, 2, mirrored(before, axis)), `${turn} ${mirror} ${axis}`).toEqual(expected);
        }
  });

  it('four turns or two mirrors come back to where they started', () => {
    let o = { x: 10, y: 20, w: 30, h: 8, turn: 0 as Turn };
    for (let i = 0; i < 4; i++) o = turned(o, 1);
    expect(o).toEqual({ x: 10, y: 20, w: 30, h: 8, turn: 0 });
    expect(turned(turned({ x: 10, y: 20, w: 30, h: 8 }, 1), -1)).toEqual({ x: 10, y: 20, w: 30, h: 8, turn: 0 });
    expect(mirrored(mirrored({ turn: 3 }, 'y'), 'y')).toEqual({ turn: 3, mirror: false });
  });

  it('turns the box about its middle, its sides swapped, and knows the frame inside it', () => {
    const t = turned({ x: 10, y: 20, w: 30, h: 8 }, 1);
    expect(t).toEqual({ x: 21, y: 9, w: 8, h: 30, turn: 1 });
    expect(frameSize(t)).toEqual({ w: 30, h: 8 });
    expect(orientationLabel({})).toBe('upright');
    expect(orientationLabel({ turn: 3, mirror: true })).toBe('mirrored, turned 270°');
  });
});
