// Where a new object goes when the pointer did not say (an imported picture): in view and free of
// every object already there, a gap apart where there is room; else free elsewhere on the bed; else where it covers the least of them.

import type { Rect } from './objects';

const overlaps = (a: Rect, b: Rect) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
const overlapArea = (a: Rect, b: Rect) =>
  Math.max(0, Math.min(a.x + a.w, b.x + b.w) - Math.max(a.x, b.x)) * Math.max(0, Math.min(a.y + a.h, b.y + b.h) - Math.max(a.y, b.y));

/**
 * Where a w × h box may start within `area` (inside it whole): in line with `middle`, on a grid half
 * a box apart, at its far edges, and beside every object, where the free gaps between objects begin.
 */
function starts(taken: readonly Rect[], w: number, h: number, area: Rect, middle: Rect): Rect[] {
  const xs = new Set<number>([middle.x]), ys = new Set<number>([middle.y]);
  // Half a box apart, and no more than about 40 a side: a tiny box on a large bed would make millions.
  const stepX = Math.max(1, Math.floor(w / 2), Math.floor(area.w / 40)), stepY = Math.max(1, Math.floor(h / 2), Math.floor(area.h / 40));
  for (let x = area.x; x + w <= area.x + area.w; x += stepX) xs.add(x);
  for (let y = area.y; y + h <= area.y + area.h; y += stepY) ys.add(y);
  xs.add(area.x + area.w - w);
  ys.add(area.y + area.h - h);
  for (const t of taken) {
    xs.add(t.x + t.w).add(t.x - w);
    ys.add(t.y + t.h).add(t.y - h);
  }
  const out: Rect[] = [];
  for (const y of ys) if (y >= area.y && y + h <= area.y + area.h) for (const x of xs) if (x >= area.x && x + w <= area.x + area.w) out.push({ x, y, w, h });
  return out;
}

/**
 * A w × h box on the cols × rows bed, nearest the middle of `visible` (what the canvas shows, in
 * cells): free of every object in `taken` and in view; else free anywhere on the bed; else, with
 * no free room left, in view where it covers the least of the others and starts on none of them,
 * so no two lie exactly one on the other. Where there is room it keeps `gap` cells from the others:
 * two boxes edge to edge drew their outlines as one line, and which board ended where was lost.
 */
export function freePlace(taken: readonly Rect[], w: number, h: number, visible: Rect, cols: number, rows: number, gap = { x: 0, y: 0 }): Rect {
  w = Math.min(w, cols);
  h = Math.min(h, rows);
  const clampX = (x: number) => Math.max(0, Math.min(cols - w, Math.round(x)));
  const clampY = (y: number) => Math.max(0, Math.min(rows - h, Math.round(y)));
  // What the view shows of the bed; a view off the bed falls back to the whole bed.
  const bed = { x: 0, y: 0, w: cols, h: rows };
  const vx0 = Math.max(0, visible.x), vy0 = Math.max(0, visible.y);
  const vx1 = Math.min(cols, visible.x + visible.w), vy1 = Math.min(rows, visible.y + visible.h);
  const view = vx1 > vx0 && vy1 > vy0 ? { x: vx0, y: vy0, w: vx1 - vx0, h: vy1 - vy0 } : bed;
  const cx = view.x + view.w / 2, cy = view.y + view.h / 2;
  const middle = { x: clampX(cx - w / 2), y: clampY(cy - h / 2), w, h };
  const dist = (r: Rect) => (r.x + w / 2 - cx) ** 2 + (r.y + h / 2 - cy) ** 2;
  const nearest = (rs: Rect[]) => rs.reduce<Rect | null>((best, r) => (!best || dist(r) < dist(best) ? r : best), null);

  const freeOf = (around: readonly Rect[]) => {
    const free = (r: Rect) => !around.some((t) => overlaps(r, t));
    return nearest([middle, ...starts(around, w, h, view, middle)].filter(free)) ?? nearest(starts(around, w, h, bed, middle).filter(free));
  };
  const apart = taken.map((t) => ({ x: t.x - gap.x, y: t.y - gap.y, w: t.w + 2 * gap.x, h: t.h + 2 * gap.y }));
  const place = freeOf(apart) ?? freeOf(taken);
  if (place) return place;
  const inView = [middle, ...starts(taken, w, h, view, middle)];
  // No free room: in view, covering the least, and never starting where another object starts.
  const cover = (r: Rect) => taken.reduce((sum, t) => sum + overlapArea(r, t), 0);
  const startsOnOne = (r: Rect) => taken.some((t) => t.x === r.x && t.y === r.y);
  const step = Math.max(1, Math.round(Math.min(w, h) / 8));
  const shifted = inView.flatMap((r) => [r, { ...r, x: clampX(r.x + step), y: clampY(r.y + step) }]);
  const open = shifted.filter((r) => !startsOnOne(r));
  const least = (open.length ? open : shifted).reduce((best, r) => {
    const d = cover(r) - cover(best);
    return d < 0 || (d === 0 && dist(r) < dist(best)) ? r : best;
  });
  return least;
}
