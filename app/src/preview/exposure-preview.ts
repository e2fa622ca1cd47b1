// The exposure preview's model: what the planned job does, stop by stop, reduced to a picture no
// bigger than the preview shows. Each bin holds the most light any of its cells got and which LED
// gave it; the travel is the head's path through the stops; the timeline is the time model's
// clock at each stop (protocol/planner.md "Time model"), so scrubbing shows time as well as place.

import type { Plan } from '../planner/plan';
import { axisSteps, stopCostUs } from '../planner/planner-wasm';
import type { MotionModel } from '../planner/time-model';
import type { PrintJob } from '../protocol/job-types';

export interface PreviewGrid {
  /** Bins across and down; each bin is `scale` × `scale` cells. */
  width: number;
  height: number;
  scale: number;
  /** The most µs any cell of the bin was lit, over the stops so far. */
  doseUs: Float32Array;
  /** 1-4: the LED that lit the bin's most-lit cell; 0: unlit. */
  led: Uint8Array;
  /** The largest `doseUs` of the whole job, so the scale does not change while scrubbing. */
  maxUs: number;
}

/** Empty bins for the job's grid, at most `maxSide` per side (maxUs still 0). */
export function emptyGrid(job: PrintJob, maxSide: number): PreviewGrid {
  const { cols, rows } = job.grid;
  const scale = Math.max(1, Math.ceil(Math.max(cols, rows) / maxSide));
  const width = Math.ceil(cols / scale), height = Math.ceil(rows / scale);
  return { width, height, scale, doseUs: new Float32Array(width * height), led: new Uint8Array(width * height), maxUs: 0 };
}

/** The job's light up to (not including) stop `upTo`, in bins of at most `maxSide` per side. */
export function previewGrid(job: PrintJob, plan: Plan, upTo: number, maxSide = 512): PreviewGrid {
  const { cols, rows } = job.grid;
  const grid = emptyGrid(job, maxSide);
  const { width, scale, doseUs, led } = grid;
  const offsets = job.leds.offsets;
  let maxUs = 0;
  for (let i = 0; i < plan.count; i++) {
    for (let k = 0; k < 4; k++) {
      const us = plan.durations[i * 4 + k];
      if (!us) continue;
      const x = plan.hx[i] + offsets[k][0], y = plan.hy[i] + offsets[k][1];
      if (x < 0 || y < 0 || x >= cols || y >= rows) continue;
      maxUs = Math.max(maxUs, us);
      if (i >= upTo) continue;
      const b = Math.floor(y / scale) * width + Math.floor(x / scale);
      if (us > doseUs[b]) (doseUs[b] = us), (led[b] = k + 1);
    }
  }
  return { ...grid, maxUs };
}

/** The time model's clock when each stop ends, µs: timeline[i] is the job's time through stop i. */
export function timeline(job: PrintJob, plan: Plan, machine: MotionModel): Float64Array {
  const out = new Float64Array(plan.count);
  // The head in steps, as the Mega keeps it.
  let x = axisSteps(machine, 0, machine.startUm[0]), y = axisSteps(machine, 1, machine.startUm[1]), t = 0;
  for (let i = 0; i < plan.count; i++) {
    const nx = axisSteps(machine, 0, job.originUm.x + plan.hx[i] * job.pitchUm.x), ny = axisSteps(machine, 1, job.originUm.y + plan.hy[i] * job.pitchUm.y);
    t += stopCostUs(machine, nx - x, ny - y, plan.durations.subarray(i * 4, i * 4 + 4));
    out[i] = t;
    x = nx, y = ny;
  }
  return out;
}

/** Each LED's share of the job's cells: how many cells it exposes. */
export function ledCoverage(plan: Plan): number[] {
  const n = [0, 0, 0, 0];
  for (let i = 0; i < plan.durations.length; i++) if (plan.durations[i]) n[i & 3]++;
  return n;
}
