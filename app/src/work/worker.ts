// The work worker: what would freeze the page (a dry run, a preview's plan, a picture decoded, a
// board read and drawn in cells) runs here. One file in the build, so it takes the flash blocks
// the Gerber reader and the planning worker took apart (docs/app.md "Size").

import { planForPreview, keptGrid } from './preview-work';
import { dryRunSummary } from './dry-run-work';
import { BoardUnreadable, rasterInWorker, readBoard, readPicture, spriteOf } from './artwork-work';
import type { Progress, WorkReply, WorkRequest } from './work-types';

type Answer = { result: unknown; transfer?: Transferable[] };

async function answer(request: WorkRequest, report: (p: Progress) => void): Promise<Answer> {
  switch (request.kind) {
    case 'plan':
      return planForPreview(request);
    case 'preview-grid':
      return keptGrid(request.upTo, request.maxSide);
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

const reply = (m: WorkReply, transfer: Transferable[] = []) => postMessage(m, { transfer });

onmessage = async (e: MessageEvent<{ id: number; request: WorkRequest }>) => {
  const { id, request } = e.data;
  try {
    const { result, transfer } = await answer(request, (progress) => reply({ id, progress }));
    reply({ id, result }, transfer);
  } catch (err) {
    reply({ id, error: (err as Error).message, ...(err instanceof BoardUnreadable ? { problems: err.problems } : {}) });
  }
};
