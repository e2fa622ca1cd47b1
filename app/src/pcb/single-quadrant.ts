// Single-quadrant arcs (G74) that sweep a quarter turn to the last bit: gerber-plotter takes a centre only if
// its sweep is at most 90°, computed with atan2, and a quarter circle between coordinates that do not subtract
// exactly (1.0575 − 1.045) comes out a hair over: the arc is skipped as "impossible", and a region's contour
// is cut there. Mentor's Xpedition draws every round cut-out of a pour as four such quarters (the MinnowBoard
// Turbot's top copper has 231). gerbv takes the best candidate; this gives the plotter that centre as a
// multi-quadrant offset, only where the plotter itself would find none.

/** An arc's coordinates as the parser gives them, in the file's units. */
export interface ArcCoord {
  x?: number;
  y?: number;
  i?: number;
  j?: number;
  a?: number;
}

/** Far below any angle a file can mean (a micro-radian is 12 nm of arc on a 12 mm radius): floating point's own error. */
const QUARTER_SLACK_RAD = 1e-6;
const TWO_PI = 2 * Math.PI;

/** The sweep from start to end about a centre, turning as the mode says, as gerber-plotter measures it. */
function sweepAbout(c: [number, number], start: [number, number], end: [number, number], mode: 'cw' | 'ccw'): number {
  let from = Math.atan2(start[1] - c[1], start[0] - c[0]);
  let to = Math.atan2(end[1] - c[1], end[0] - c[0]);
  if (mode === 'cw') from = from >= to ? from : from + TWO_PI;
  else to = to >= from ? to : to + TWO_PI;
  return Math.abs(from - to);
}

/**
 * The centre of a single-quadrant arc that gerber-plotter would skip although one of its candidates lies at the
 * radius from both ends (within the file's epsilon) and sweeps a quarter turn within floating point's error;
 * null when the plotter finds a centre itself, or when none is near (a truly impossible arc, which it says).
 */
export function quarterArcCentre(start: [number, number], coord: ArcCoord, mode: 'cw' | 'ccw', epsilon: number): [number, number] | null {
  if (coord.a) return null; // an arc given by its radius: the plotter's other path
  const i = coord.i ?? 0;
  const j = coord.j ?? 0;
  const r = Math.hypot(i, j);
  const end: [number, number] = [coord.x ?? start[0], coord.y ?? start[1]];
  const xs = i ? [start[0] + i, start[0] - i] : [start[0]];
  const ys = j ? [start[1] + j, start[1] - j] : [start[1]];
  const onCircle = xs
    .flatMap((x) => ys.map((y): [number, number] => [x, y]))
    .filter((c) => Math.abs(Math.hypot(start[0] - c[0], start[1] - c[1]) - r) <= epsilon && Math.abs(Math.hypot(end[0] - c[0], end[1] - c[1]) - r) <= epsilon);
  if (onCircle.some((c) => sweepAbout(c, start, end, mode) <= Math.PI / 2)) return null;
  return onCircle.find((c) => sweepAbout(c, start, end, mode) <= Math.PI / 2 + QUARTER_SLACK_RAD) ?? null;
}
