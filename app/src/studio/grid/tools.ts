// The grid editor's raster tools as plain functions over an edit: brush, eraser (a brush of
// dose 0), line, rectangle (outline or filled) and flood fill.

import type { DoseGrid } from './grid';
import type { Edit } from './history';

/** A round stamp `size` cells across (1 = one cell), centred on (cx, cy). */
export function stamp(grid: DoseGrid, edit: Edit, cx: number, cy: number, size: number, dose: number): void {
  const r = (Math.max(1, size) - 1) / 2;
  const x0 = Math.max(0, Math.ceil(cx - r)), x1 = Math.min(grid.cols - 1, Math.floor(cx + r));
  const y0 = Math.max(0, Math.ceil(cy - r)), y1 = Math.min(grid.rows - 1, Math.floor(cy + r));
  if (x0 > x1 || y0 > y1) return;
  edit.touch(x0, y0, x1, y1);
  const r2 = (r + 0.5) * (r + 0.5);
  for (let y = y0; y <= y1; y++)
    for (let x = x0; x <= x1; x++) if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r2) grid.cells[y * grid.cols + x] = dose;
}

/** A line of stamps from (x0, y0) to (x1, y1): every cell between, none skipped at any angle. */
export function line(grid: DoseGrid, edit: Edit, x0: number, y0: number, x1: number, y1: number, size: number, dose: number): void {
  x0 = Math.round(x0), y0 = Math.round(y0), x1 = Math.round(x1), y1 = Math.round(y1);
  const dx = Math.abs(x1 - x0), dy = -Math.abs(y1 - y0);
  const sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  let err = dx + dy;
  for (;;) {
    stamp(grid, edit, x0, y0, size, dose);
    if (x0 === x1 && y0 === y1) return;
    const e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

/** A rectangle between two corners: its outline `size` cells wide, or filled. */
export function rectangle(grid: DoseGrid, edit: Edit, x0: number, y0: number, x1: number, y1: number, filled: boolean, size: number, dose: number): void {
  const l = Math.max(0, Math.min(x0, x1)), r = Math.min(grid.cols - 1, Math.max(x0, x1));
  const t = Math.max(0, Math.min(y0, y1)), b = Math.min(grid.rows - 1, Math.max(y0, y1));
  if (l > r || t > b) return;
  if (filled) {
    edit.touch(l, t, r, b);
    for (let y = t; y <= b; y++) grid.cells.fill(dose, y * grid.cols + l, y * grid.cols + r + 1);
    return;
  }
  const w = Math.max(1, Math.round(size));
  rectangle(grid, edit, l, t, r, Math.min(b, t + w - 1), true, 1, dose);
  rectangle(grid, edit, l, Math.max(t, b - w + 1), r, b, true, 1, dose);
  rectangle(grid, edit, l, t, Math.min(r, l + w - 1), b, true, 1, dose);
  rectangle(grid, edit, Math.max(l, r - w + 1), t, r, b, true, 1, dose);
}

/**
 * Fills the 4-connected area of cells that have the same dose as (x, y) with `dose`, a row
 * span at a time, with an explicit stack: a 4096² area must not overflow the call stack.
 * Returns how many cells changed.
 */
export function floodFill(grid: DoseGrid, edit: Edit, x: number, y: number, dose: number): number {
  if (!grid.inside(x, y)) return 0;
  const { cols, rows, cells } = grid;
  const target = cells[y * cols + x];
  if (target === dose) return 0;
  let changed = 0;
  const stack: number[] = [x, y];
  while (stack.length) {
    const sy = stack.pop()!, sx = stack.pop()!;
    let l = sx;
    const row = sy * cols;
    if (cells[row + l] !== target) continue;
    while (l > 0 && cells[row + l - 1] === target) l--;
    let r = sx;
    while (r < cols - 1 && cells[row + r + 1] === target) r++;
    edit.touch(l, sy, r, sy);
    cells.fill(dose, row + l, row + r + 1);
    changed += r - l + 1;
    for (const ny of [sy - 1, sy + 1]) {
      if (ny < 0 || ny >= rows) continue;
      const nrow = ny * cols;
      let inSpan = false;
      for (let nx = l; nx <= r; nx++) {
        const match = cells[nrow + nx] === target;
        if (match && !inSpan) stack.push(nx, ny);
        inSpan = match;
      }
    }
  }
  return changed;
}
