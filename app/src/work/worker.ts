// The work worker: what would freeze the page (a dry run, a preview's plan, a picture decoded, a
// board read and drawn in cells) runs here. One file in the build, so it takes the flash blocks
// the Gerber reader and the planning worker took apart (docs/app.md "Size").

import { answer, BoardUnreadable } from './answer';
import type { WorkReply, WorkRequest } from './work-types';

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
