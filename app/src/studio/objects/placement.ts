// Where a new object goes when the pointer did not say (an imported picture): in view and free,
// never exactly on the one before it.

import type { Rect } from './objects';

const overlaps = (a: Rect, b: Rect) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;

/**
 * A w × h box on the cols × rows bed: the free place nearest the middle of `visible` (what the
 * canvas shows, in cells), trying places half a box apart. When nothing in view is free, the middle,
 * stepped down and right past every object that already starts there, so no two lie exactly one on
 * the other.
 */
export function freePlace(taken: readonly Rect[], w: number, h: number, visible: Rect, cols: number, rows: number): Rect {
  w = Math.min(w, cols);
  h = Math.min(h, rows);
  const clampX = (x: number) => Math.max(0, Math.min(cols - w, Math.round(x)));
  const clampY = (y: number) => Math.max(0, Math.min(rows - h, Math.round(y)));
  // What the view shows of the bed; a view off the bed falls back to the whole bed.
  const vx0 = Math.max(0, visible.x), vy0 = Math.max(0, visible.y);
  const vx1 = Math.min(cols, visible.x + visible.w), vy1 = Math.min(rows, visible.y + visible.h);
  const view = vx1 > vx0 && vy1 > vy0 ? { x: vx0, y: vy0, w: vx1 - vx0, h: vy1 - vy0 } : { x: 0, y: 0, w: cols, h: rows };
  const cx = view.x + view.w / 2, cy = view.y + view.h / 2;
  const stepX = Math.max(1, Math.floor(w / 2)), stepY = Math.max(1, Math.floor(h / 2));
  const candidates: Rect[] = [];
  for (let y = view.y; y + h <= view.y + view.h; y += stepY)
    for (let x = view.x; x + w <= view.x + view.w; x += stepX) candidates.push({ x, y, w, h });
  const middle = { x: clampX(cx - w / 2), y: clampY(cy - h / 2), w, h };
  candidates.push(middle);
  const dist = (r: Rect) => (r.x + w / 2 - cx) ** 2 + (r.y + h / 2 - cy) ** 2;
  candidates.sort((a, b) => dist(a) - dist(b));
  const free = candidates.find((r) => !taken.some((t) => overlaps(r, t)));
  if (free) return free;
  // Nothing free in view: a cascade from the middle, one step per object already there.
  const step = Math.max(1, Math.round(Math.min(w, h) / 8));
  let r = middle;
  for (let i = 0; i < taken.length + 1 && taken.some((t) => t.x === r.x && t.y === r.y); i++) r = { x: clampX(r.x + step), y: clampY(r.y + step), w, h };
  return r;
}
