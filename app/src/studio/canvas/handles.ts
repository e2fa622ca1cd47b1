// Where the selected object's corner handles sit on the screen. On a box small on the screen (new
// text at the overview's zoom) they sit outside its corners, so they do not hide what they hold
// (issue 29, item 14); on a larger one they sit on its corners.

import { CORNERS, cornerOf, type Corner, type Rect } from '../objects/objects';
import { toScreen, type View } from './viewport';

/** A handle's side, in CSS pixels. */
export const HANDLE_PX = 8;
/** Below this many pixels across or down, the handles move outside the box. */
export const SMALL_PX = 6 * HANDLE_PX;

/** Each corner's handle, by its middle on the screen. */
export function handleCentres(v: View, r: Rect): { corner: Corner; x: number; y: number }[] {
  const outside = r.w * v.scale < SMALL_PX || r.h * v.scale < SMALL_PX ? HANDLE_PX / 2 : 0;
  return CORNERS.map((corner) => {
    const p = toScreen(v, cornerOf(r, corner).x, cornerOf(r, corner).y);
    return { corner, x: p.x + (corner[1] === 'w' ? -outside : outside), y: p.y + (corner[0] === 'n' ? -outside : outside) };
  });
}

/** The selection frame's line width, CSS pixels. */
export const FRAME_PX = 2;

/**
 * The rectangle the selection frame's line is drawn on: just outside the object (the line covers 1 to
 * 3 px off its box), so on a small one, new text at the overview's zoom, it hides none of the glyphs.
 */
export function selectionFrame(v: View, r: Rect): { x: number; y: number; w: number; h: number } {
  const at = toScreen(v, r.x, r.y);
  return { x: Math.round(at.x) - FRAME_PX, y: Math.round(at.y) - FRAME_PX, w: Math.round(r.w * v.scale) + 2 * FRAME_PX, h: Math.round(r.h * v.scale) + 2 * FRAME_PX };
}

/** The handle under the screen point (sx, sy), if any: within a handle's side of its middle. */
export function handleAt(v: View, r: Rect, sx: number, sy: number): Corner | null {
  return handleCentres(v, r).find((h) => Math.abs(h.x - sx) <= HANDLE_PX && Math.abs(h.y - sy) <= HANDLE_PX)?.corner ?? null;
}
