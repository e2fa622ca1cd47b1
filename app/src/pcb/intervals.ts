// Sets of intervals along one scan line, as flat sorted lists [a0, b0, a1, b1, …] of disjoint [a, b]: union, difference, intersection.

/**
 * A growable list of interval ends. Emptying it (`length = 0`) keeps its storage: a scan line's lists are
 * refilled thousands of times per board, and a plain array set to length 0 would give its storage back.
 */
export class Intervals {
  v: Float64Array;
  /** Values in use: twice the number of intervals. */
  length = 0;

  constructor(capacity = 16) {
    this.v = new Float64Array(capacity);
  }

  static of(...values: number[]): Intervals {
    const l = new Intervals(Math.max(2, values.length));
    for (const x of values) l.v[l.length++] = x;
    return l;
  }

  push(lo: number, hi: number): void {
    if (this.length + 2 > this.v.length) {
      const v = new Float64Array(this.v.length * 2);
      v.set(this.v);
      this.v = v;
    }
    this.v[this.length++] = lo;
    this.v[this.length++] = hi;
  }

  /** Appends every interval of another list. */
  append(other: Intervals): void {
    for (let i = 0; i < other.length; i += 2) this.push(other.v[i], other.v[i + 1]);
  }

  toArray(): number[] {
    return Array.from(this.v.subarray(0, this.length));
  }
}

let starts = new Float64Array(64);
let ends = new Float64Array(64);

/** Any intervals, overlapping and in any order, as one sorted disjoint list (touching ones merge). */
export function unionAll(raw: Intervals, out: Intervals): Intervals {
  out.length = 0;
  const n = raw.length >> 1;
  const r = raw.v;
  if (n === 0) return out;
  if (n === 1) {
    out.push(r[0], r[1]);
    return out;
  }
  if (starts.length < n) {
    starts = new Float64Array(n * 2);
    ends = new Float64Array(n * 2);
  }
  for (let i = 0; i < n; i++) {
    starts[i] = r[2 * i];
    ends[i] = r[2 * i + 1];
  }
  const s = sorted(starts, n);
  const e = sorted(ends, n);
  // Sweep starts and ends in order: an interval of the union closes where the count of open ones falls to 0.
  let i = 0;
  let j = 0;
  let open = 0;
  let from = 0;
  while (j < n) {
    if (i < n && s[i] <= e[j]) {
      if (open++ === 0) from = s[i];
      i++;
    } else {
      if (--open === 0) out.push(from, e[j]);
      j++;
    }
  }
  return out;
}

/**
 * The first n values sorted in place. The rasteriser hands over spans nearly in order (it orders each row's
 * shapes by their left edge), which insertion sorts in about one pass; very long lists go to the typed sort.
 */
function sorted(v: Float64Array, n: number): Float64Array {
  if (n > 256) {
    v.subarray(0, n).sort();
    return v;
  }
  for (let i = 1; i < n; i++) {
    const x = v[i];
    let k = i - 1;
    for (; k >= 0 && v[k] > x; k--) v[k + 1] = v[k];
    v[k + 1] = x;
  }
  return v;
}

/** a ∪ b, both sorted and disjoint. */
export function union(a: Intervals, b: Intervals, out: Intervals): Intervals {
  out.length = 0;
  const av = a.v;
  const bv = b.v;
  let i = 0;
  let j = 0;
  while (i < a.length || j < b.length) {
    let lo: number;
    let hi: number;
    if (j >= b.length || (i < a.length && av[i] <= bv[j])) {
      lo = av[i];
      hi = av[i + 1];
      i += 2;
    } else {
      lo = bv[j];
      hi = bv[j + 1];
      j += 2;
    }
    const last = out.length - 1;
    if (last > 0 && lo <= out.v[last]) {
      if (hi > out.v[last]) out.v[last] = hi;
    } else {
      out.push(lo, hi);
    }
  }
  return out;
}

/** a − b, both sorted and disjoint. */
export function subtract(a: Intervals, b: Intervals, out: Intervals): Intervals {
  out.length = 0;
  const av = a.v;
  const bv = b.v;
  let j = 0;
  for (let i = 0; i < a.length; i += 2) {
    let lo = av[i];
    const hi = av[i + 1];
    while (j < b.length && bv[j + 1] <= lo) j += 2;
    let k = j;
    while (k < b.length && bv[k] < hi) {
      if (bv[k] > lo) out.push(lo, bv[k]);
      lo = Math.max(lo, bv[k + 1]);
      k += 2;
    }
    if (lo < hi) out.push(lo, hi);
  }
  return out;
}

/** a ∩ b, both sorted and disjoint. */
export function intersect(a: Intervals, b: Intervals, out: Intervals): Intervals {
  out.length = 0;
  const av = a.v;
  const bv = b.v;
  let i = 0;
  let j = 0;
  while (i < a.length && j < b.length) {
    const lo = Math.max(av[i], bv[j]);
    const hi = Math.min(av[i + 1], bv[j + 1]);
    if (lo < hi) out.push(lo, hi);
    if (av[i + 1] < bv[j + 1]) i += 2;
    else j += 2;
  }
  return out;
}
