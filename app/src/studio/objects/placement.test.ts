import { describe, expect, it } from 'vitest';
import { freePlace } from './placement';

const bed = { cols: 4000, rows: 4000 };
const view = { x: 1000, y: 1000, w: 2000, h: 1500 };
type Box = { x: number; y: number; w: number; h: number };
const overlap = (a: Box, b: Box) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;

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
  it('keeps a gap from the others where there is room, and goes edge to edge only where there is not', () => {
    const gap = { x: 40, y: 40 };
    const first = freePlace([], 400, 300, view, bed.cols, bed.rows, gap);
    const second = freePlace([first], 400, 300, view, bed.cols, bed.rows, gap);
    const apart = Math.max(second.x - (first.x + first.w), first.x - (second.x + second.w), second.y - (first.y + first.h), first.y - (second.y + second.h));
    expect(apart).toBe(40);
    // A bed with room for the box only edge to edge beside the one there: it goes there.
    const narrow = { x: 0, y: 0, w: 700, h: 300 };
    expect(freePlace([{ x: 0, y: 0, w: 300, h: 300 }], 400, 300, narrow, 700, 300, gap)).toEqual({ x: 300, y: 0, w: 400, h: 300 });
  });
  it('with no room left, covers the least and starts on no other object', () => {
    const full = [{ x: 0, y: 0, w: 4000, h: 4000 }];
    const first = freePlace(full, 400, 300, view, bed.cols, bed.rows);
    const second = freePlace([...full, first], 400, 300, view, bed.cols, bed.rows);
    expect(second).not.toEqual(first);
    expect(overlap(second, first)).toBe(false);
    const third = freePlace([...full, first, second], 400, 300, view, bed.cols, bed.rows);
    expect(overlap(third, first) || overlap(third, second)).toBe(false);
  });
  // Issue 29, item 14: a later import landed on older objects, as only the one before was avoided.
  it('avoids every older object, finding the gap beside them', () => {
    const small = { cols: 1000, rows: 1000 };
    const whole = { x: 0, y: 0, w: 1000, h: 1000 };
    const older = [{ x: 0, y: 0, w: 700, h: 1000 }];
    expect(freePlace(older, 300, 300, whole, small.cols, small.rows)).toEqual({ x: 700, y: 350, w: 300, h: 300 });
    const scattered = [{ x: 0, y: 0, w: 420, h: 420 }, { x: 580, y: 0, w: 420, h: 420 }, { x: 0, y: 580, w: 420, h: 420 }, { x: 580, y: 580, w: 420, h: 420 }];
    const r = freePlace(scattered, 150, 150, whole, small.cols, small.rows);
    for (const t of scattered) expect(overlap(r, t)).toBe(false);
  });
  it('goes elsewhere on the bed, free, before it would cover an object in view', () => {
    const inView = [{ x: 1000, y: 1000, w: 2000, h: 1500 }];
    const r = freePlace(inView, 400, 300, view, bed.cols, bed.rows);
    expect(overlap(r, inView[0])).toBe(false);
    expect(r.x >= 0 && r.y >= 0 && r.x + r.w <= bed.cols && r.y + r.h <= bed.rows).toBe(true);
  });
  it('places twelve imports in turn, none on any other', () => {
    const taken: { x: number; y: number; w: number; h: number }[] = [];
    for (let i = 0; i < 12; i++) {
      const r = freePlace(taken, 400, 300, view, bed.cols, bed.rows);
      for (const t of taken) expect(overlap(r, t), `import ${i}`).toBe(false);
      taken.push(r);
    }
  });
  it('stays on the bed when the view is off it', () => {
    const r = freePlace([], 400, 300, { x: -5000, y: -5000, w: 100, h: 100 }, bed.cols, bed.rows);
    expect(r).toEqual({ x: 1800, y: 1850, w: 400, h: 300 });
  });
});
