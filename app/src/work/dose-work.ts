// The delivered dose followed in the work worker: the job's records planned and kept here, the page's
// dose ledger mirrored a batch of changed stops at a time (job/dose-batch.ts), each cell counted
// (job/dose-map.ts DoseTally) and the map binned into the canvas's pixels, handed over. A whole bed's
// first count and each drawing of its map took 80–170 ms on the page's thread; the page now only puts the pixels.

import { LedgerMirror, type DoseBatch } from '../job/dose-batch';
import { doseImage } from '../job/dose-colours';
import { DoseTally, type DoseMapView } from '../job/dose-map';
import { planDoses, type DosePlan } from '../job/dose-plan';
import type { MotionModel } from '../planner/time-model';
import type { PrintJob } from '../protocol/job-types';

/** What the page needs of a planned job's records before any report: its grid and its steps. */
export type DosePlanShape = Pick<DosePlan, 'cols' | 'rows' | 'unit' | 'steps'>;

let kept: DoseTally | null = null;
const mirror = new LedgerMirror();

/** Plans the job that ran and keeps its records here; the next map counts the mirrored ledger afresh against them. */
export function keepDosePlan(job: PrintJob, machine: MotionModel): DosePlanShape {
  const plan = planDoses(job, machine);
  kept = new DoseTally(plan);
  return { cols: plan.cols, rows: plan.rows, unit: plan.unit, steps: plan.steps };
}

/** Takes the page's batch, counts the steps it changed, and gives the map's words and its pixels (handed over). */
export function doseMapNow(batch: DoseBatch, maxSide: number): { result: DoseMapView; transfer: Transferable[] } {
  mirror.apply(batch);
  if (!kept) throw new Error('no job is planned for its delivered dose yet');
  const m = kept.update(mirror);
  const image = doseImage(m, maxSide);
  const { cols, rows, counts, twiceSteps, cutSteps, worst, unit, steps } = m;
  return { result: { cols, rows, counts, twiceSteps, cutSteps, worst, unit, steps, image }, transfer: [image.pixels.buffer] };
}
