import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { intersect, subtract, union, unionAll, type Intervals } from './intervals';

/** Whether x lies in one of the (closed) intervals. */
const inside = (l: Intervals, x: number) => l.some((_, i) => i % 2 === 0 && l[i] <= x && x <= l[i + 1]);

const raw = fc.array(fc.tuple(fc.integer({ min: 0, max: 100 }), fc.integer({ min: 1, max: 30 })), { maxLength: 12 }).map((l) => l.flatMap(([a, w]) => [a, a + w]));
const set = raw.map((l) => unionAll(l, []));

// Probe between integers too, so that touching ends and single points are told apart from gaps.
const probes = Array.from({ length: 270 }, (_, i) => i / 2 + 0.25);

describe('interval sets on a scan line', () => {
  it('unions any intervals into a sorted disjoint list covering the same points', () => {
    fc.assert(
      fc.property(raw, (r) => {
        const u = unionAll(r, []);
        for (let i = 2; i < u.length; i += 2) expect(u[i]).toBeGreaterThan(u[i - 1]);
        for (const x of probes) expect(inside(u, x)).toBe(inside(r, x));
      }),
    );
    expect(unionAll([5, 7, 1, 3, 3, 4], [])).toEqual([1, 4, 5, 7]); // touching intervals merge
  });

  it('adds, takes away and intersects sets point by point', () => {
    fc.assert(
      fc.property(set, set, (a, b) => {
        const u = union(a, b, []);
        const d = subtract(a, b, []);
        const n = intersect(a, b, []);
        for (const x of probes) {
          expect(inside(u, x)).toBe(inside(a, x) || inside(b, x));
          // Away from b's ends (where a closed interval's end point sits), a − b is a without b.
          if (!b.includes(Math.floor(x)) && !b.includes(Math.ceil(x))) expect(inside(d, x)).toBe(inside(a, x) && !inside(b, x));
          if (inside(n, x)) expect(inside(a, x) && inside(b, x)).toBe(true);
        }
      }),
    );
    expect(subtract([0, 10], [2, 3, 5, 6], [])).toEqual([0, 2, 3, 5, 6, 10]);
    expect(intersect([0, 4, 6, 10], [3, 7], [])).toEqual([3, 4, 6, 7]);
  });
});
