// The work worker's preview: the plan made for the preview, kept, and its light up to a stop or
// pass binned for the canvas, so scrubbing a whole bed's plan never runs on the page's thread.

import { previewGrid, type PreviewGrid } from '../preview/exposure-preview';
import { planJob, type Planned, type PlanRequest } from '../preview/plan-work';
import { scanPreviewGrid } from '../preview/scan-preview';
import type { MotionModel } from '../planner/time-model';
import type { PrintJob } from '../protocol/job-types';

let kept: { job: PrintJob; planned: Planned } | null = null;

/** The plan, kept for `keptGrid`; the page gets copies of its arrays, handed over (`transfer`). */
export function planForPreview(req: PlanRequest): { result: Planned; transfer: Transferable[] } {
  const planned = planJob(req);
  kept = { job: { ...req.job, strategy: { ...req.job.strategy, name: planned.order } }, planned };
  const plan = { ...planned.plan, hx: planned.plan.hx.slice(), hy: planned.plan.hy.slice(), durations: planned.plan.durations.slice() };
  const clock = planned.clock.slice();
  // A scan's light per cell stays here: the page draws only what keptGrid bins of it.
  const scan = planned.scan && { ...planned.scan, doses: { from: new Uint32Array(0), cell: new Uint32Array(0), led: new Uint8Array(0), us: new Float64Array(0) } };
  return { result: { ...planned, plan, clock, scan }, transfer: [plan.hx.buffer, plan.hy.buffer, plan.durations.buffer, clock.buffer] };
}

/** The kept plan's light up to stop (or pass) `upTo`. */
export function keptGrid(upTo: number, maxSide: number): { result: PreviewGrid; transfer: Transferable[] } {
  if (!kept) throw new Error('nothing is planned yet');
  const { job, planned } = kept;
  const grid = planned.scan ? scanPreviewGrid(job, planned.scan.doses, upTo, maxSide) : previewGrid(job, planned.plan, upTo, maxSide);
  return { result: grid, transfer: [grid.doseUs.buffer, grid.led.buffer] };
}
