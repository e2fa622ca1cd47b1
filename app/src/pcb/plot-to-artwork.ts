// Turns the plotter's image objects into this app's artwork: shapes in millimetres, polarity and step-and-repeat applied.
import { EMPTY_BOX, paint, translate, translatePaint, unionBox, type BoxMm, type Paint, type Shape } from './artwork';
import type { PadPrimitive, Plot, Point, Segment } from './tracespace';

/** Arcs become chords no further than this from the true arc: 0.1 µm, far below a cell. */
export const ARC_TOLERANCE_MM = 1e-4;
/**
 * A draw with a zero-width aperture is drawn this wide. Eagle draws its outline so (%ADD10C,0.0000*%), and gerbv
 * shows such lines a pixel wide: left at no width they would expose nothing and offer no cutting guide.
 * Two cells at the machine's 50 µm, so a 50 % threshold keeps the line wherever it lies.
 */
export const HAIRLINE_MM = 0.1;
/**
 * An arc whose end lies further than this from the circle its start and centre make cannot be drawn as written
 * (or three steps of the file's coordinates, if more: rounding to them moves the ends and the centre).
 */
export const ARC_MISMATCH_MM = 0.01;

/** A flash in a drill file: where the drill goes, and its size. */
export interface Hole {
  x: number;
  y: number;
  diameterMm: number;
}

/**
 * A slot a drill file cuts along a straight run with one tool (Excellon's G85 between two holes, or a
 * routed path): its ends and the tool's diameter. A routed arc comes as chords along it.
 */
export interface Slot {
  x0: number;
  y0: number;
  x1: number;
  y1: number;
  diameterMm: number;
}

export interface Artwork {
  paints: Paint[];
  holes: Hole[];
  /** The slots of a drill file (drawn in paints too, as strokes the tool's width). Empty for other files. */
  slots: Slot[];
  /** What the dark paints cover; EMPTY_BOX when nothing is drawn. */
  boundsMm: BoxMm;
  /** The same with draws taken by their centre lines: an outline's board edge, whatever width it is drawn with. */
  lineBoundsMm: BoxMm;
  /** Pads flashed with a tool the file never defined, which the plotter skips. */
  unknownTools: string[];
  /** Apertures with no shape at all (a macro that is not defined or draws nothing): their flashes are left out. */
  shapelessTools: string[];
  /** Shapes left out because a size or place in them is not a number (a macro short of parameters). */
  malformed: number;
  /** Draws with a zero-width aperture: drawn HAIRLINE_MM wide, and bounded by their centre lines (a hairline has no width of its own). */
  hairlines: number;
  /** Arcs whose start and end lie at different distances from their centre (the plotter draws them all the same). */
  impossibleArcs: number;
}

const MM_PER_INCH = 25.4;

export function plotToArtwork(plot: Plot, arcSlackMm = ARC_MISMATCH_MM): Artwork {
  const k = plot.units === 'in' ? MM_PER_INCH : 1;
  const pads = new Map<string, Shape>();
  const diameters = new Map<string, number>();
  const paints: Paint[] = [];
  const holes: Hole[] = [];
  const slots: Slot[] = [];
  const unknownTools = new Set<string>();
  const shapelessTools = new Set<string>();
  let malformed = 0;
  let hairlines = 0;
  let impossibleArcs = 0;
  let clear = false;
  // Draws' paints and their half widths: bounded by their centre lines where the board's edge is asked for.
  const drawn = new Map<Paint, { r: number; hair: boolean }>();
  // Step and repeat: what is drawn while a repeat is on is gathered and laid down once per offset when it ends.
  let offsets: Point[] = [];
  let block: Paint[] = [];
  const add = (shape: Shape, line?: { r: number; hair: boolean }) => {
    const p = paint(shape, clear);
    if ([p.box.x0, p.box.y0, p.box.x1, p.box.y1].some((v) => Number.isNaN(v))) malformed++;
    else {
      (offsets.length ? block : paints).push(p);
      if (line) drawn.set(p, line);
    }
  };
  const endRepeat = () => {
    for (const [dx, dy] of offsets)
      for (const p of block) {
        const copy = dx === 0 && dy === 0 ? p : translatePaint(p, dx * k, dy * k);
        if (drawn.has(p)) drawn.set(copy, drawn.get(p)!);
        paints.push(copy);
      }
    block = [];
    offsets = [];
  };

  for (const o of plot.objects) {
    switch (o.type) {
      case 'shape': {
        const block = plot.blocks?.get(o.tool);
        // A block aperture's flash lays its artwork down: its parts dark or clear as the block drew them.
        pads.set(o.tool, block ? { kind: 'stack', parts: plotToArtwork(block).paints.map((p) => ({ shape: p.shape, clear: p.clear })) } : padShape(o.shape, k));
        const first = o.shape[0];
        if (first?.type === 'circle') diameters.set(o.tool, 2 * first.r * k);
        break;
      }
      case 'pad': {
        const pad = pads.get(o.tool);
        if (!pad) {
          unknownTools.add(o.tool);
          break;
        }
        if (pad.kind === 'stack' && pad.parts.length === 0) {
          shapelessTools.add(o.tool);
          break;
        }
        const x = o.x * k;
        const y = o.y * k;
        add(moveShape(pad, x, y));
        if (plot.filetype === 'drill') holes.push({ x, y, diameterMm: diameters.get(o.tool) ?? 0 });
        break;
      }
      case 'stroke': {
        const hair = !(o.width > 0);
        if (hair) hairlines++;
        impossibleArcs += o.path.filter((s) => arcMismatch(s) * k > arcSlackMm).length;
        const r = hair ? HAIRLINE_MM / 2 : (o.width / 2) * k;
        for (const s of strokeShapes(o.path, r, k)) add(s, { r, hair });
        if (plot.filetype === 'drill') slots.push(...slotRuns(o.path, o.width * k, k));
        break;
      }
      case 'fill':
        impossibleArcs += o.path.filter((s) => arcMismatch(s) * k > arcSlackMm).length;
        add({ kind: 'polygon', rings: contours(o.path, k) });
        break;
      case 'polarity':
        clear = o.polarity === 'clear';
        break;
      case 'repeat':
        endRepeat();
        offsets = o.offsets;
        break;
      case 'size':
        break;
    }
  }
  endRepeat();

  const centre = (p: Paint, r: number) => ({ x0: p.box.x0 + r, y0: p.box.y0 + r, x1: p.box.x1 - r, y1: p.box.y1 - r });
  let boundsMm = EMPTY_BOX;
  let lineBoundsMm = EMPTY_BOX;
  for (const p of paints) {
    if (p.clear) continue;
    const line = drawn.get(p);
    // A hairline has no width of its own: it is bounded by its centre line even as drawn.
    boundsMm = unionBox(boundsMm, line?.hair ? centre(p, line.r) : p.box);
    lineBoundsMm = unionBox(lineBoundsMm, line ? centre(p, line.r) : p.box);
  }
  return { paints, holes, slots, boundsMm, lineBoundsMm, unknownTools: [...unknownTools], shapelessTools: [...shapelessTools], malformed, hairlines, impossibleArcs };
}

/**
 * How much further from an arc's centre its end lies than its start, in the file's units. In multi-quadrant
 * mode the plotter takes the centre the file gives without checking it, and the arc ends with a jump.
 */
export function arcMismatch(s: Segment): number {
  if (s.type !== 'arc' || s.sweep >= 2 * Math.PI) return 0;
  const [cx, cy] = s.center;
  return Math.abs(Math.hypot(s.end[0] - cx, s.end[1] - cy) - Math.hypot(s.start[0] - cx, s.start[1] - cy));
}

function moveShape(s: Shape, x: number, y: number): Shape {
  return x === 0 && y === 0 ? s : translate(s, x, y);
}

/** An aperture's primitives as one shape: the primitive itself when it is alone and dark, else a stack. */
export function padShape(primitives: PadPrimitive[], k: number): Shape {
  const parts: { shape: Shape; clear: boolean }[] = [];
  let clear = false;
  for (const p of primitives) {
    if (p.type === 'layer') clear = p.polarity === 'clear';
    else parts.push({ shape: primitiveShape(p, k), clear });
  }
  return parts.length === 1 && !parts[0].clear ? parts[0].shape : { kind: 'stack', parts };
}

function primitiveShape(p: Exclude<PadPrimitive, { type: 'layer' }>, k: number): Shape {
  switch (p.type) {
    case 'circle':
      return { kind: 'circle', cx: p.cx * k, cy: p.cy * k, r: p.r * k };
    case 'rect':
      return { kind: 'rect', x0: (p.cx - p.width / 2) * k, y0: (p.cy - p.height / 2) * k, x1: (p.cx + p.width / 2) * k, y1: (p.cy + p.height / 2) * k, r: p.r * k };
    case 'poly':
      return { kind: 'polygon', rings: [Float64Array.from(p.points.flat(), (v) => v * k)] };
    case 'ring': {
      const outer: Shape = { kind: 'circle', cx: p.cx * k, cy: p.cy * k, r: (p.r + p.width / 2) * k };
      const inner = (p.r - p.width / 2) * k;
      return inner > 0 ? { kind: 'stack', parts: [{ shape: outer, clear: false }, { shape: { ...outer, r: inner }, clear: true }] } : outer;
    }
    case 'clip':
      return { kind: 'clip', shape: padShape(p.shape, k), within: primitiveShape(p.clip as Exclude<PadPrimitive, { type: 'layer' }>, k) };
  }
}

/** The points along a segment after its start, arcs as chords within ARC_TOLERANCE_MM. */
function segmentPoints(s: Segment, k: number, out: number[]): void {
  if (s.type === 'line') {
    out.push(s.end[0] * k, s.end[1] * k);
    return;
  }
  const r = s.radius * k;
  const step = r > ARC_TOLERANCE_MM ? 2 * Math.acos(1 - ARC_TOLERANCE_MM / r) : Math.PI / 2;
  const n = Math.max(1, Math.ceil(s.sweep / step));
  const sign = s.dir === 'ccw' ? 1 : -1;
  const [cx, cy] = s.center;
  for (let i = 1; i < n; i++) {
    const a = s.start[2] + (sign * s.sweep * i) / n;
    out.push((cx + s.radius * Math.cos(a)) * k, (cy + s.radius * Math.sin(a)) * k);
  }
  out.push(s.end[0] * k, s.end[1] * k);
}

/** A stroke as stadiums, one per straight piece; a draw that goes nowhere leaves a dot. */
function strokeShapes(path: Segment[], r: number, k: number): Shape[] {
  if (r <= 0) return [];
  const shapes: Shape[] = [];
  const pts: number[] = [];
  for (const s of path) {
    pts.length = 0;
    pts.push(s.start[0] * k, s.start[1] * k);
    segmentPoints(s, k, pts);
    for (let i = 2; i < pts.length; i += 2) {
      const [x0, y0, x1, y1] = [pts[i - 2], pts[i - 1], pts[i], pts[i + 1]];
      shapes.push(x0 === x1 && y0 === y1 ? { kind: 'circle', cx: x0, cy: y0, r } : { kind: 'stadium', x0, y0, x1, y1, r });
    }
  }
  return shapes;
}

/** A region's path as closed rings: a new ring starts wherever a segment does not begin where the last ended. */
function contours(path: Segment[], k: number): Float64Array[] {
  const rings: Float64Array[] = [];
  let ring: number[] = [];
  let end: Point | null = null;
  const close = () => {
    if (ring.length >= 6) rings.push(Float64Array.from(ring));
    ring = [];
  };
  for (const s of path) {
    if (!end || s.start[0] !== end[0] || s.start[1] !== end[1]) {
      close();
      ring.push(s.start[0] * k, s.start[1] * k);
    }
    segmentPoints(s, k, ring);
    end = [s.end[0], s.end[1]];
  }
  close();
  return rings;
}

/** A drill file's stroke (a G85 slot, a routed path) as straight runs of the tool, in mm; arcs as chords. */
function slotRuns(path: readonly Segment[], diameterMm: number, k: number): Slot[] {
  const runs: Slot[] = [];
  for (const s of path) {
    const points = [s.start[0] * k, s.start[1] * k];
    segmentPoints(s, k, points);
    for (let i = 2; i < points.length; i += 2) runs.push({ x0: points[i - 2], y0: points[i - 1], x1: points[i], y1: points[i + 1], diameterMm });
  }
  return runs;
}
