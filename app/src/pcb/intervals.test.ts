import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { intersect, Intervals, subtract, union, unionAll } from './intervals';

/** Whether x lies in one of the (closed) intervals. */
const inside = (v: number[], x: number) => v.some((_, i) => i % 2 === 0 && v[i] <= x && x <= v[i + 1]);
const fresh = () => new Intervals(2);

const raw = fc.array(fc.tuple(fc.integer({ min: 0, max: 100 }), fc.integer({ min: 1, max: 30 })), { maxLength: 12 }).map((l) => Intervals.of(...l.flatMap(([a, w]) => [a, a + w])));
const set = raw.map((l) => unionAll(l, fresh()));

// Probe between integers too, so that touching ends and single points are told apart from gaps.
const probes = Array.from({ length: 270 }, (_, i) => i / 2 + 0.25);

describe('interval sets on a scan line', () => {
  it('unions any intervals into a sorted disjoint list covering the same points', () => {
    fc.assert(
      fc.property(raw, (r) => {
        const u = unionAll(r, fresh()).toArray();
        const rv = r.toArray();
        const sorted = u.every((v, i) => i < 2 || i % 2 === 1 || v > u[i - 1]);
        return sorted && probes.every((x) => inside(u, x) === inside(rv, x));
      }),
    );
    expect(unionAll(Intervals.of(5, 7, 1, 3, 3, 4), fresh()).toArray()).toEqual([1, 4, 5, 7]); // touching intervals merge
  });

  it('adds, takes away and intersects sets point by point', () => {
    fc.assert(
      fc.property(set, set, (a, b) => {
        const u = union(a, b, fresh()).toArray();
        const d = subtract(a, b, fresh()).toArray();
        const n = intersect(a, b, fresh()).toArray();
        const [av, bv] = [a.toArray(), b.toArray()];
        return probes.every(
          (x) =>
            inside(u, x) === (inside(av, x) || inside(bv, x)) &&
            // Away from b's ends (where a closed interval's end point sits), a − b is a without b.
            (bv.includes(Math.floor(x)) || bv.includes(Math.ceil(x)) || inside(d, x) === (inside(av, x) && !inside(bv, x))) &&
            (!inside(n, x) || (inside(av, x) && inside(bv, x))),
        );
      }),
    );
    expect(subtract(Intervals.of(0, 10), Intervals.of(2, 3, 5, 6), fresh()).toArray()).toEqual([0, 2, 3, 5, 6, 10]);
    expect(intersect(Intervals.of(0, 4, 6, 10), Intervals.of(3, 7), fresh()).toArray()).toEqual([3, 4, 6, 7]);
  });

  it('keeps its storage when emptied and grows when filled', () => {
    const l = new Intervals(2);
    for (let i = 0; i < 100; i++) l.push(i, i + 0.5);
    const storage = l.v;
    l.length = 0;
    l.push(1, 2);
    expect(l.v).toBe(storage);
    expect(l.toArray()).toEqual([1, 2]);
  });
});
