// Where a shape crosses one horizontal scan line: the exact x intervals it covers there (curves included, no flattening).
import type { Shape } from './artwork';
import { intersect, Intervals, subtract, union, unionAll } from './intervals';

/**
 * A shape made ready for scanning. `spans` appends the intervals the shape covers on the line at height y,
 * possibly overlapping and unsorted; callers union them. Polygons keep a list of the edges under way, so a
 * source scans fastest from the top down (it starts over if asked about a line above the last one).
 */
export interface SpanSource {
  spans(y: number, out: Intervals): void;
}

export function spanSource(s: Shape): SpanSource {
  switch (s.kind) {
    case 'circle':
      return { spans: (y, out) => circleSpan(s.cx, s.cy, s.r, y, out) };
    case 'stadium':
      return stadium(s.x0, s.y0, s.x1, s.y1, s.r);
    case 'rect':
      return { spans: (y, out) => roundedRectSpan(s.x0, s.y0, s.x1, s.y1, s.r, y, out) };
    case 'polygon': {
      const rings = s.rings.map((r) => new RingScan(r));
      return { spans: (y, out) => rings.forEach((r) => r.spans(y, out)) };
    }
    case 'stack':
      return stack(s.parts.map((p) => ({ source: spanSource(p.shape), clear: p.clear })));
    case 'clip': {
      const shape = spanSource(s.shape);
      const within = spanSource(s.within);
      const [raw, a, b, both] = [new Intervals(), new Intervals(), new Intervals(), new Intervals()];
      return {
        spans(y, out) {
          raw.length = 0;
          shape.spans(y, raw);
          if (raw.length === 0) return;
          unionAll(raw, a);
          raw.length = 0;
          within.spans(y, raw);
          unionAll(raw, b);
          out.append(intersect(a, b, both));
        },
      };
    }
  }
}

/**
 * Appends [lo, hi], merged into the last interval when the two overlap: the pieces of one trace follow each
 * other in a file, so this keeps the lists that get sorted short.
 */
function add(out: Intervals, lo: number, hi: number): void {
  const n = out.length;
  const v = out.v;
  if (n > 0 && lo <= v[n - 1] && hi >= v[n - 2]) {
    if (lo < v[n - 2]) v[n - 2] = lo;
    if (hi > v[n - 1]) v[n - 1] = hi;
  } else {
    out.push(lo, hi);
  }
}

function circleSpan(cx: number, cy: number, r: number, y: number, out: Intervals): void {
  const d = y - cy;
  const h2 = r * r - d * d;
  if (h2 > 0) {
    const h = Math.sqrt(h2);
    add(out, cx - h, cx + h);
  }
}

function roundedRectSpan(x0: number, y0: number, x1: number, y1: number, r: number, y: number, out: Intervals): void {
  if (y <= y0 || y >= y1) return;
  if (r <= 0) {
    add(out, x0, x1);
    return;
  }
  const d = y < y0 + r ? y0 + r - y : y > y1 - r ? y - (y1 - r) : 0;
  const inset = r - Math.sqrt(Math.max(0, r * r - d * d));
  if (x0 + inset < x1 - inset) add(out, x0 + inset, x1 - inset);
}

/** The segment (x0,y0)–(x1,y1) drawn with a round pen of radius r: two end circles and the band between. */
function stadium(x0: number, y0: number, x1: number, y1: number, r: number): SpanSource {
  const dx = x1 - x0;
  const dy = y1 - y0;
  const len2 = dx * dx + dy * dy;
  const rLen = r * Math.sqrt(len2);
  return {
    spans(y, out) {
      let lo = Infinity;
      let hi = -Infinity;
      const h0 = r * r - (y - y0) * (y - y0);
      if (h0 > 0) {
        const h = Math.sqrt(h0);
        lo = x0 - h;
        hi = x0 + h;
      }
      const h1 = r * r - (y - y1) * (y - y1);
      if (h1 > 0) {
        const h = Math.sqrt(h1);
        lo = Math.min(lo, x1 - h);
        hi = Math.max(hi, x1 + h);
      }
      // The band: points within r of the segment's line whose foot falls between its ends. With u = x − x0
      // and v = y − y0: |dx·v − dy·u| ≤ r·|d| and 0 ≤ dx·u + dy·v ≤ |d|².
      const v = y - y0;
      let uLo = -Infinity;
      let uHi = Infinity;
      if (dy === 0) {
        if (Math.abs(v) >= r) uHi = -Infinity;
      } else {
        const a = (dx * v - rLen) / dy;
        const b = (dx * v + rLen) / dy;
        uLo = Math.min(a, b);
        uHi = Math.max(a, b);
      }
      if (dx === 0) {
        if (dy * v < 0 || dy * v > len2) uHi = -Infinity;
      } else {
        const a = -(dy * v) / dx;
        const b = (len2 - dy * v) / dx;
        uLo = Math.max(uLo, Math.min(a, b));
        uHi = Math.min(uHi, Math.max(a, b));
      }
      if (uLo < uHi) {
        lo = Math.min(lo, x0 + uLo);
        hi = Math.max(hi, x0 + uHi);
      }
      if (lo < hi) add(out, lo, hi);
    },
  };
}

/** Parts in order, each dark part added and each clear one taken away, within the stack only. */
function stack(parts: { source: SpanSource; clear: boolean }[]): SpanSource {
  const [raw, part] = [new Intervals(), new Intervals()];
  let acc = new Intervals();
  let next = new Intervals();
  return {
    spans(y, out) {
      acc.length = 0;
      for (const p of parts) {
        raw.length = 0;
        p.source.spans(y, raw);
        if (raw.length === 0) continue;
        unionAll(raw, part);
        (p.clear ? subtract : union)(acc, part, next);
        const done = next;
        next = acc;
        acc = done;
      }
      out.append(acc);
    },
  };
}

/**
 * One closed ring, filled by the non-zero winding rule. Edges under way are kept in order of x from line to
 * line; lines a fraction of a cell apart barely reorder them, so an insertion sort keeps them ordered cheaply
 * even for a copper pour of thousands of edges.
 */
class RingScan implements SpanSource {
  readonly #top: Float64Array; // per edge, in order of falling top: top y, bottom y, x at top, dx/dy, direction
  readonly #bottom: Float64Array;
  readonly #xTop: Float64Array;
  readonly #slope: Float64Array;
  readonly #dir: Int8Array;
  #next = 0;
  #lastY = Infinity;
  #active: Int32Array = new Int32Array(16);
  #xs: Float64Array = new Float64Array(16);
  #count = 0;

  constructor(ring: Float64Array) {
    const n = ring.length >> 1;
    const edges: [number, number, number, number, number][] = [];
    for (let i = 0; i < n; i++) {
      const j = (i + 1) % n;
      const [xa, ya, xb, yb] = [ring[2 * i], ring[2 * i + 1], ring[2 * j], ring[2 * j + 1]];
      if (ya === yb) continue; // a horizontal edge crosses no scan line
      const up = yb > ya;
      edges.push([up ? yb : ya, up ? ya : yb, up ? xb : xa, (xb - xa) / (yb - ya), up ? 1 : -1]);
    }
    edges.sort((a, b) => b[0] - a[0]);
    this.#top = Float64Array.from(edges, (e) => e[0]);
    this.#bottom = Float64Array.from(edges, (e) => e[1]);
    this.#xTop = Float64Array.from(edges, (e) => e[2]);
    this.#slope = Float64Array.from(edges, (e) => e[3]);
    this.#dir = Int8Array.from(edges, (e) => e[4]);
  }

  spans(y: number, out: Intervals): void {
    const top = this.#top;
    const bottom = this.#bottom;
    if (y > this.#lastY) {
      this.#next = 0;
      this.#count = 0;
    }
    this.#lastY = y;
    // An edge crosses the line when bottom ≤ y < top: half-open, so a vertex shared by two edges counts once.
    let m = 0;
    let active: Int32Array = this.#active;
    for (let i = 0; i < this.#count; i++) if (bottom[active[i]] <= y) active[m++] = active[i];
    for (; this.#next < top.length && top[this.#next] > y; this.#next++) {
      if (bottom[this.#next] > y) continue; // begins and ends between two lines
      if (m === active.length) {
        active = this.#grow(m);
      }
      active[m++] = this.#next;
    }
    this.#count = m;
    if (m < 2) return;

    const xs = this.#xs;
    for (let i = 0; i < m; i++) xs[i] = this.#xTop[active[i]] + (y - top[active[i]]) * this.#slope[active[i]];
    for (let i = 1; i < m; i++) {
      const x = xs[i];
      const e = active[i];
      let k = i - 1;
      for (; k >= 0 && xs[k] > x; k--) {
        xs[k + 1] = xs[k];
        active[k + 1] = active[k];
      }
      xs[k + 1] = x;
      active[k + 1] = e;
    }
    let winding = 0;
    let from = 0;
    for (let i = 0; i < m; i++) {
      const before = winding;
      winding += this.#dir[active[i]];
      if (before === 0 && winding !== 0) from = xs[i];
      else if (before !== 0 && winding === 0 && xs[i] > from) out.push(from, xs[i]);
    }
  }

  #grow(m: number): Int32Array {
    const active = new Int32Array(m * 2);
    active.set(this.#active);
    this.#active = active;
    this.#xs = new Float64Array(m * 2);
    return active;
  }
}
