// Turning and mirroring artwork before it is rasterised: a bottom layer seen from above, or a board laid at an angle on the bed.
import { EMPTY_BOX, shapeBox, unionBox, type BoxMm, type Paint, type Shape } from './artwork';
import type { BoardLayer } from './read-board';

/** Applied about the board's origin: first mirror (x → −x) if asked, then a counter-clockwise turn. */
export interface Orientation {
  mirror?: boolean;
  rotateDeg?: number;
}

type Point = [number, number];

export const isIdentity = (o: Orientation | undefined): boolean => !o || (!o.mirror && !((o.rotateDeg ?? 0) % 360));

/** The paints oriented; shapes stay exact (a turned rectangle becomes a polygon, its round corners circles). */
export function orientPaints(paints: readonly Paint[], o: Orientation): Paint[] {
  const map = pointMap(o);
  const quarter = quarterTurns(o.rotateDeg ?? 0);
  return paints.map((p) => {
    const shape = orientShape(p.shape, map, quarter);
    return { shape, clear: p.clear, box: shapeBox(shape) };
  });
}

/** A layer oriented: its artwork, its holes and its bounds. */
export function orientLayer(l: BoardLayer, o: Orientation): BoardLayer {
  const paints = orientPaints(l.paints, o);
  const map = pointMap(o);
  const holes = l.holes.map((h) => {
    const [x, y] = map(h.x, h.y);
    return { x, y, diameterMm: h.diameterMm };
  });
  const slots = l.slots.map((s) => {
    const [x0, y0] = map(s.x0, s.y0);
    const [x1, y1] = map(s.x1, s.y1);
    return { x0, y0, x1, y1, diameterMm: s.diameterMm };
  });
  const boundsMm = paints.reduce((b, p) => (p.clear ? b : unionBox(b, p.box)), EMPTY_BOX);
  return { ...l, paints, holes, slots, boundsMm, ...(l.lineBoundsMm && { lineBoundsMm: orientBox(l.lineBoundsMm, o) }) };
}

export function orientBox(b: BoxMm, o: Orientation): BoxMm {
  const map = pointMap(o);
  const corners = [map(b.x0, b.y0), map(b.x1, b.y0), map(b.x0, b.y1), map(b.x1, b.y1)];
  const xs = corners.map((c) => c[0]);
  const ys = corners.map((c) => c[1]);
  return { x0: Math.min(...xs), y0: Math.min(...ys), x1: Math.max(...xs), y1: Math.max(...ys) };
}

export function pointMap(o: Orientation): (x: number, y: number) => Point {
  const deg = (((o.rotateDeg ?? 0) % 360) + 360) % 360;
  // Whole quarter turns are written out, so that they move coordinates without rounding.
  const [cos, sin] = deg === 0 ? [1, 0] : deg === 90 ? [0, 1] : deg === 180 ? [-1, 0] : deg === 270 ? [0, -1] : [Math.cos((deg * Math.PI) / 180), Math.sin((deg * Math.PI) / 180)];
  const m = o.mirror ? -1 : 1;
  return (x, y) => [cos * m * x - sin * y, sin * m * x + cos * y];
}

/** 0–3 for a whole number of quarter turns, else null. */
function quarterTurns(deg: number): number | null {
  const d = ((deg % 360) + 360) % 360;
  return d % 90 === 0 ? d / 90 : null;
}

function orientShape(s: Shape, map: (x: number, y: number) => Point, quarter: number | null): Shape {
  switch (s.kind) {
    case 'circle': {
      const [cx, cy] = map(s.cx, s.cy);
      return { kind: 'circle', cx, cy, r: s.r };
    }
    case 'stadium': {
      const [x0, y0] = map(s.x0, s.y0);
      const [x1, y1] = map(s.x1, s.y1);
      return { kind: 'stadium', x0, y0, x1, y1, r: s.r };
    }
    case 'rect':
      if (quarter !== null) {
        const [ax, ay] = map(s.x0, s.y0);
        const [bx, by] = map(s.x1, s.y1);
        return { kind: 'rect', x0: Math.min(ax, bx), y0: Math.min(ay, by), x1: Math.max(ax, bx), y1: Math.max(ay, by), r: s.r };
      }
      return turnedRect(s, map);
    case 'polygon':
      return {
        kind: 'polygon',
        rings: s.rings.map((ring) => {
          const out = new Float64Array(ring.length);
          for (let i = 0; i < ring.length; i += 2) [out[i], out[i + 1]] = map(ring[i], ring[i + 1]);
          return out;
        }),
      };
    case 'stack':
      return { kind: 'stack', parts: s.parts.map((p) => ({ shape: orientShape(p.shape, map, quarter), clear: p.clear })) };
    case 'clip':
      return { kind: 'clip', shape: orientShape(s.shape, map, quarter), within: orientShape(s.within, map, quarter) };
  }
}

/** A rectangle at an angle: a polygon, or with round corners the union of two crossed polygons and four circles. */
function turnedRect(s: Extract<Shape, { kind: 'rect' }>, map: (x: number, y: number) => Point): Shape {
  const quad = (x0: number, y0: number, x1: number, y1: number): Shape => ({ kind: 'polygon', rings: [Float64Array.from([map(x0, y0), map(x1, y0), map(x1, y1), map(x0, y1)].flat())] });
  const r = Math.min(s.r, (s.x1 - s.x0) / 2, (s.y1 - s.y0) / 2);
  if (r <= 0) return quad(s.x0, s.y0, s.x1, s.y1);
  const parts: Shape[] = [quad(s.x0 + r, s.y0, s.x1 - r, s.y1), quad(s.x0, s.y0 + r, s.x1, s.y1 - r)];
  for (const [x, y] of [
    [s.x0 + r, s.y0 + r],
    [s.x1 - r, s.y0 + r],
    [s.x1 - r, s.y1 - r],
    [s.x0 + r, s.y1 - r],
  ]) {
    const [cx, cy] = map(x, y);
    parts.push({ kind: 'circle', cx, cy, r });
  }
  return { kind: 'stack', parts: parts.map((shape) => ({ shape, clear: false })) };
}
