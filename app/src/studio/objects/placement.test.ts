import { describe, expect, it } from 'vitest';
import { freePlace } from './placement';

const bed = { cols: 4000, rows: 4000 };
const view = { x: 1000, y: 1000, w: 2000, h: 1500 };

describe('where a new object goes', () => {
  it('in the middle of the view when it is free', () => {
    expect(freePlace([], 400, 300, view, bed.cols, bed.rows)).toEqual({ x: 1800, y: 1600, w: 400, h: 300 });
  });
  it('never on the one before: each next import lands free and in view', () => {
    const taken = [];
    for (let i = 0; i < 6; i++) {
      const r = freePlace(taken, 400, 300, view, bed.cols, bed.rows);
      for (const t of taken) expect(r.x < t.x + t.w && t.x < r.x + r.w && r.y < t.y + t.h && t.y < r.y + r.h).toBe(false);
      expect(r.x).toBeGreaterThanOrEqual(view.x);
      expect(r.y).toBeGreaterThanOrEqual(view.y);
      expect(r.x + r.w).toBeLessThanOrEqual(view.x + view.w);
      expect(r.y + r.h).toBeLessThanOrEqual(view.y + view.h);
      taken.push(r);
    }
  });
  it('with no room in view, steps past the ones already at the middle', () => {
    const full = [{ x: 0, y: 0, w: 4000, h: 4000 }];
    const first = freePlace(full, 400, 300, view, bed.cols, bed.rows);
    const second = freePlace([...full, first], 400, 300, view, bed.cols, bed.rows);
    expect(second).not.toEqual(first);
    expect(second.x).toBeGreaterThan(first.x);
  });
  it('stays on the bed when the view is off it', () => {
    const r = freePlace([], 400, 300, { x: -5000, y: -5000, w: 100, h: 100 }, bed.cols, bed.rows);
    expect(r).toEqual({ x: 1800, y: 1850, w: 400, h: 300 });
  });
});
