// Framing: the head traces where a job's light will land, with the LEDs off, so the maker can see the
// pattern's place on the board before anything is exposed.

import type { PrintJob } from '../protocol/job-types';

const mm = (um: number) => (um / 1000).toFixed(3).replace(/\.?0+$/, '');

/**
 * The moves that take the first LED's spot round the job's cells: the four corners of the area the
 * cells cover, clockwise from the origin and back, absolute, at the travel speed (mm/s).
 */
export function framingMoves(job: PrintJob, travelMmS: number): string[] {
  const [dx, dy] = job.leds.offsets[0] ?? [0, 0];
  const x0 = job.originUm.x - dx * job.pitchUm.x, y0 = job.originUm.y - dy * job.pitchUm.y;
  const x1 = x0 + job.grid.cols * job.pitchUm.x, y1 = y0 + job.grid.rows * job.pitchUm.y;
  const f = Math.round(travelMmS * 60);
  const corners: [number, number][] = [[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]];
  return ['G90', ...corners.map(([x, y]) => `G0 X${mm(x)} Y${mm(y)} F${f}`)];
}
