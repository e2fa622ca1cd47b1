// What the work worker does with each kind of request (worker.ts wires it to its messages; a test
// runs it in the same thread): the answer, and the buffers to hand over rather than copy.

import { planForPreview, keptGrid } from './preview-work';
import { dryRunSummary } from './dry-run-work';
import { doseMapNow, keepDosePlan } from './dose-work';
import { BoardUnreadable, rasterInWorker, readBoard, readPicture, spriteOf } from './artwork-work';
import { plannerReady } from '../planner/planner-wasm';
import type { Progress, WorkRequest } from './work-types';

export { BoardUnreadable };

type Answer = { result: unknown; transfer?: Transferable[] };

/** What plans a job: the Mega's planner as WebAssembly, fetched before the first of them. */
const PLANS = new Set<WorkRequest['kind']>(['plan', 'dose-plan', 'dry-run']);

export async function answer(request: WorkRequest, report: (p: Progress) => void): Promise<Answer> {
  if (PLANS.has(request.kind)) await plannerReady();
  switch (request.kind) {
    case 'plan':
      return planForPreview(request);
    case 'preview-grid':
      return keptGrid(request.upTo, request.maxSide);
    case 'dose-plan':
      return { result: keepDosePlan(request.job, request.machine) };
    case 'dose-map':
      return doseMapNow(request.batch, request.maxSide);
    case 'dry-run':
      return { result: dryRunSummary(request, report) };
    case 'read-picture':
      return { result: await readPicture(request.src, report) };
    case 'read-board':
      return { result: readBoard(request, report) };
    case 'raster': {
      const raster = await rasterInWorker(request.object, request.polarity, report);
      const sprite = spriteOf(raster, request.object.w, request.object.h);
      return { result: { raster, sprite }, transfer: [raster.buffer, ...(sprite ? [sprite] : [])] };
    }
  }
}

