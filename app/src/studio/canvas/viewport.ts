// Where the grid sits on the screen: a scale (screen pixels per cell) and the cell at the view's
// top-left corner. Zoom keeps the cell under the pointer where it is.

export interface View {
  /** Screen pixels per cell. */
  scale: number;
  /** The cell coordinate at the canvas's top-left corner (fractional). */
  x: number;
  y: number;
}

export const MIN_SCALE = 1 / 64;
/** The rulers' width along the top and left of the canvas, in CSS pixels. */
export const RULER = 22;
export const MAX_SCALE = 64;

export function toCell(v: View, sx: number, sy: number): { x: number; y: number } {
  return { x: v.x + sx / v.scale, y: v.y + sy / v.scale };
}

export function toScreen(v: View, cx: number, cy: number): { x: number; y: number } {
  return { x: (cx - v.x) * v.scale, y: (cy - v.y) * v.scale };
}

/** Zooms by `factor` about the screen point (sx, sy). */
export function zoomAt(v: View, factor: number, sx: number, sy: number): View {
  const scale = Math.min(MAX_SCALE, Math.max(MIN_SCALE, v.scale * factor));
  const c = toCell(v, sx, sy);
  return { scale, x: c.x - sx / scale, y: c.y - sy / scale };
}

export function panBy(v: View, dxScreen: number, dyScreen: number): View {
  return { ...v, x: v.x - dxScreen / v.scale, y: v.y - dyScreen / v.scale };
}

/** The whole grid in a canvas of w × h pixels, centred in the part the rulers leave, with a margin. */
export function fit(cols: number, rows: number, w: number, h: number, margin = 16, ruler = 0): View {
  const aw = w - ruler, ah = h - ruler;
  const scale = Math.min(MAX_SCALE, Math.max(MIN_SCALE, Math.min((aw - 2 * margin) / cols, (ah - 2 * margin) / rows)));
  return { scale, x: cols / 2 - (ruler + aw / 2) / scale, y: rows / 2 - (ruler + ah / 2) / scale };
}

/** Ruler ticks in mm for the visible span: a step of 1, 2 or 5 × 10^k that leaves ≥ `minPx` between labels. */
export function rulerStep(pxPerMm: number, minPx = 60): number {
  const raw = minPx / pxPerMm;
  const k = Math.pow(10, Math.floor(Math.log10(raw)));
  for (const m of [1, 2, 5, 10]) if (m * k >= raw) return m * k;
  return 10 * k;
}
