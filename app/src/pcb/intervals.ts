// Sets of intervals along one scan line, as flat sorted lists [a0, b0, a1, b1, …] of disjoint [a, b]: union, difference, intersection.

export type Intervals = number[];

let starts = new Float64Array(64);
let ends = new Float64Array(64);

/** Any intervals, overlapping and in any order, as one sorted disjoint list (touching ones merge). */
export function unionAll(raw: Intervals, out: Intervals): Intervals {
  out.length = 0;
  const n = raw.length >> 1;
  if (n === 0) return out;
  if (n === 1) {
    out.push(raw[0], raw[1]);
    return out;
  }
  if (starts.length < n) {
    starts = new Float64Array(n * 2);
    ends = new Float64Array(n * 2);
  }
  for (let i = 0; i < n; i++) {
    starts[i] = raw[2 * i];
    ends[i] = raw[2 * i + 1];
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
  let i = 0;
  let j = 0;
  while (i < a.length || j < b.length) {
    let lo: number;
    let hi: number;
    if (j >= b.length || (i < a.length && a[i] <= b[j])) {
      lo = a[i];
      hi = a[i + 1];
      i += 2;
    } else {
      lo = b[j];
      hi = b[j + 1];
      j += 2;
    }
    const last = out.length - 1;
    if (last > 0 && lo <= out[last]) {
      if (hi > out[last]) out[last] = hi;
    } else {
      out.push(lo, hi);
    }
  }
  return out;
}

/** a − b, both sorted and disjoint. */
export function subtract(a: Intervals, b: Intervals, out: Intervals): Intervals {
  out.length = 0;
  let j = 0;
  for (let i = 0; i < a.length; i += 2) {
    let lo = a[i];
    const hi = a[i + 1];
    while (j < b.length && b[j + 1] <= lo) j += 2;
    let k = j;
    while (k < b.length && b[k] < hi) {
      if (b[k] > lo) out.push(lo, b[k]);
      lo = Math.max(lo, b[k + 1]);
      k += 2;
    }
    if (lo < hi) out.push(lo, hi);
  }
  return out;
}

/** a ∩ b, both sorted and disjoint. */
export function intersect(a: Intervals, b: Intervals, out: Intervals): Intervals {
  out.length = 0;
  let i = 0;
  let j = 0;
  while (i < a.length && j < b.length) {
    const lo = Math.max(a[i], b[j]);
    const hi = Math.min(a[i + 1], b[j + 1]);
    if (lo < hi) out.push(lo, hi);
    if (a[i + 1] < b[j + 1]) i += 2;
    else j += 2;
  }
  return out;
}
