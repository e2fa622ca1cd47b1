// Turning and mirroring objects, alike for every kind: an object draws its cells upright in its own
// frame, and its orientation (a left-to-right mirror, then quarter turns clockwise) moves them onto
// its box on the bed. Turning an object turns its box about its middle; mirroring leaves the box.

import type { Rect, StudioObject, Turn } from './objects';

type Oriented = Pick<StudioObject, 'turn' | 'mirror'>;

/** The size of the object's own frame: its box, with the sides swapped by an odd turn. */
export function frameSize(o: Rect & Oriented): { w: number; h: number } {
  return (o.turn ?? 0) & 1 ? { w: o.h, h: o.w } : { w: o.w, h: o.h };
}

/** The box on the bed for a frame of w × h cells under the object's turn. */
export function boxSize(o: Oriented, w: number, h: number): { w: number; h: number } {
  return (o.turn ?? 0) & 1 ? { w: h, h: w } : { w, h };
}

/**
 * Cells of the object's own frame (w × h, row 0 first) as they lie on the bed: mirrored left to
 * right if it is mirrored, then turned. The same cells come back when nothing is turned.
 */
export function orient<T extends Uint8Array>(cells: T, w: number, h: number, o: Oriented): T {
  const turn = o.turn ?? 0, mirror = o.mirror ?? false;
  if (turn === 0 && !mirror) return cells;
  const out = new Uint8Array(cells.length) as T;
  const bw = turn & 1 ? h : w, bh = turn & 1 ? w : h;
  for (let y = 0; y < bh; y++)
    for (let x = 0; x < bw; x++) {
      // The frame's cell (u, v) that lands on the bed's (x, y).
      let u: number, v: number;
      if (turn === 0) (u = x), (v = y);
      else if (turn === 1) (u = y), (v = h - 1 - x);
      else if (turn === 2) (u = w - 1 - x), (v = h - 1 - y);
      else (u = w - 1 - y), (v = x);
      if (mirror) u = w - 1 - u;
      out[y * bw + x] = cells[v * w + u];
    }
  return out;
}

/** A quarter turn clockwise (1) or anticlockwise (-1) about the box's middle. */
export function turned(o: Rect & Oriented, by: 1 | -1): Rect & { turn: Turn } {
  const turn = (((o.turn ?? 0) + by + 4) % 4) as Turn;
  return { x: o.x + Math.round((o.w - o.h) / 2), y: o.y + Math.round((o.h - o.w) / 2), w: o.h, h: o.w, turn };
}

/**
 * Mirrored across the bed's X (left to right) or Y (top to bottom) as it lies now. A mirror
 * after a turn is the mirror before the opposite turn, so the orientation stays "mirror, then turn".
 */
export function mirrored(o: Oriented, axis: 'x' | 'y'): { turn: Turn; mirror: boolean } {
  const turn = o.turn ?? 0;
  return { turn: (((axis === 'x' ? 0 : 2) - turn + 4) % 4) as Turn, mirror: !(o.mirror ?? false) };
}

/** The orientation in words: "upright", "turned 90°", "mirrored, turned 180°". */
export function orientationLabel(o: Oriented): string {
  const turn = o.turn ?? 0;
  const parts = [...(o.mirror ? ['mirrored'] : []), ...(turn ? [`turned ${turn * 90}°`] : [])];
  return parts.length ? parts.join(', ') : 'upright';
}
