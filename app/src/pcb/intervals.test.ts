import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { intersect, Intervals, subtract, union, unionAll } from './intervals';

/** Whether x lies in one of the (closed) intervals. */
const inside = (l: Intervals | number[], x: number) => {
  const v = l instanceof Intervals ? l.toArray() : l;
  return v.some((_, i) => i % 2 === 0 && v[i] <= x && x <= v[i + 1]);
};
const fresh = () => new Intervals(2);

const raw = fc.array(fc.tuple(fc.integer({ min: 0, max: 100 }), fc.integer({ min: 1, max: 30 })), { maxLength: 12 }).map((l) => Intervals.of(...l.flatMap(([a, w]) => [a, a + w])));
const set = raw.map((l) => unionAll(l, fresh()));

// Probe between integers too, so that touching ends and single points are told apart from gaps.
const probes = Array.from({ length: 270 }, (_, i) => i / 2 + 0.25);

describe('interval sets on a scan line', () => {
  it('unions any intervals into a sorted disjoint list covering the same points', () => {
    fc.assert(
      fc.property(raw, (r) => {
        const u = unionAll(r, fresh());
        for (let i = 2; i < u.length; i += 2) expect(u.v[i]).toBeGreaterThan(u.v[i - 1]);
        for (const x of probes) expect(inside(u, x)).toBe(inside(r, x));
      }),
    );
    expect(unionAll(Intervals.of(5, 7, 1, 3, 3, 4), fresh()).toArray()).toEqual([1, 4, 5, 7]); // touching intervals merge
  });

  it('adds, takes away and intersects sets point by point', () => {
    fc.assert(
      fc.property(set, set, (a, b) => {
        const u = union(a, b, fresh());
        const d = subtract(a, b, fresh());
        const n = intersect(a, b, fresh());
        for (const x of probes) {
          expect(inside(u, x)).toBe(inside(a, x) || inside(b, x));
          // Away from b's ends (where a closed interval's end point sits), a − b is a without b.
          if (!b.toArray().includes(Math.floor(x)) && !b.toArray().includes(Math.ceil(x))) expect(inside(d, x)).toBe(inside(a, x) && !inside(b, x));
          if (inside(n, x)) expect(inside(a, x) && inside(b, x)).toBe(true);
        }
      }),
    );
    expect(subtract(Intervals.of(0, 10), Intervals.of(2, 3, 5, 6), fresh()).toArray()).toEqual([0, 2, 3, 5, 6, 10]);
    expect(intersect(Intervals.of(0, 4, 6, 10), Intervals.of(3, 7), fresh()).toArray()).toEqual([3, 4, 6, 7]);
  });
});
