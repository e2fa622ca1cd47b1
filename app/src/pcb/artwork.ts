// A board layer's artwork as plain shapes in board millimetres (Y up), drawn in file order, dark or clear.

export interface BoxMm {
  x0: number;
  y0: number;
  x1: number;
  y1: number;
}

/**
 * The shapes the rasteriser knows. Each is filled. A stadium is a stroked segment with round ends (a circular
 * aperture drawn from one point to another); a rect may have round corners (an obround aperture). A polygon's
 * rings are each filled by the non-zero rule and unioned, as a region's contours are in Gerber.
 * A stack is an aperture built of parts, some of them clear: a clear part takes away from the stack only
 * (an aperture's hole or a macro's exposure-off primitive does not erase what lies under the flash).
 * A clip is `shape` cut to `within` (a macro's thermal).
 */
export type Shape =
  | { kind: 'circle'; cx: number; cy: number; r: number }
  | { kind: 'stadium'; x0: number; y0: number; x1: number; y1: number; r: number }
  | { kind: 'rect'; x0: number; y0: number; x1: number; y1: number; r: number }
  | { kind: 'polygon'; rings: Float64Array[] }
  | { kind: 'stack'; parts: { shape: Shape; clear: boolean }[] }
  | { kind: 'clip'; shape: Shape; within: Shape };

/** One drawing operation of a layer: a shape added (dark) or taken away (clear, Gerber's LPC). */
export interface Paint {
  shape: Shape;
  clear: boolean;
  box: BoxMm;
}

export const EMPTY_BOX: BoxMm = { x0: Infinity, y0: Infinity, x1: -Infinity, y1: -Infinity };

export const isEmptyBox = (b: BoxMm): boolean => !(b.x1 >= b.x0 && b.y1 >= b.y0);

export function unionBox(a: BoxMm, b: BoxMm): BoxMm {
  return { x0: Math.min(a.x0, b.x0), y0: Math.min(a.y0, b.y0), x1: Math.max(a.x1, b.x1), y1: Math.max(a.y1, b.y1) };
}

export function shapeBox(s: Shape): BoxMm {
  switch (s.kind) {
    case 'circle':
      return { x0: s.cx - s.r, y0: s.cy - s.r, x1: s.cx + s.r, y1: s.cy + s.r };
    case 'stadium':
      return { x0: Math.min(s.x0, s.x1) - s.r, y0: Math.min(s.y0, s.y1) - s.r, x1: Math.max(s.x0, s.x1) + s.r, y1: Math.max(s.y0, s.y1) + s.r };
    case 'rect':
      return { x0: s.x0, y0: s.y0, x1: s.x1, y1: s.y1 };
    case 'polygon': {
      let b = EMPTY_BOX;
      for (const ring of s.rings) {
        for (let i = 0; i < ring.length; i += 2) b = unionBox(b, { x0: ring[i], y0: ring[i + 1], x1: ring[i], y1: ring[i + 1] });
      }
      return b;
    }
    case 'stack':
      // Clear parts only cut: the dark parts bound the stack.
      return s.parts.filter((p) => !p.clear).reduce((b, p) => unionBox(b, shapeBox(p.shape)), EMPTY_BOX);
    case 'clip': {
      const a = shapeBox(s.shape);
      const w = shapeBox(s.within);
      return { x0: Math.max(a.x0, w.x0), y0: Math.max(a.y0, w.y0), x1: Math.min(a.x1, w.x1), y1: Math.min(a.y1, w.y1) };
    }
  }
}

/** The shape moved by (dx, dy): a flash of an aperture, or a step-and-repeat copy. */
export function translate(s: Shape, dx: number, dy: number): Shape {
  switch (s.kind) {
    case 'circle':
      return { ...s, cx: s.cx + dx, cy: s.cy + dy };
    case 'stadium':
    case 'rect':
      return { ...s, x0: s.x0 + dx, y0: s.y0 + dy, x1: s.x1 + dx, y1: s.y1 + dy };
    case 'polygon':
      return {
        kind: 'polygon',
        rings: s.rings.map((ring) => ring.map((v, i) => v + (i % 2 === 0 ? dx : dy))),
      };
    case 'stack':
      return { kind: 'stack', parts: s.parts.map((p) => ({ shape: translate(p.shape, dx, dy), clear: p.clear })) };
    case 'clip':
      return { kind: 'clip', shape: translate(s.shape, dx, dy), within: translate(s.within, dx, dy) };
  }
}

export function paint(shape: Shape, clear: boolean): Paint {
  return { shape, clear, box: shapeBox(shape) };
}

export function translatePaint(p: Paint, dx: number, dy: number): Paint {
  return { shape: translate(p.shape, dx, dy), clear: p.clear, box: { x0: p.box.x0 + dx, y0: p.box.y0 + dy, x1: p.box.x1 + dx, y1: p.box.y1 + dy } };
}
