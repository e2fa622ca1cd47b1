// A job's cells copied into one buffer of their own, to be handed to the work worker by transfer
// rather than cloned: `postMessage` cloning a whole bed's 16 MB of rows took 38–58 ms of the page's
// thread on a busy machine, the longest task of a dry run and of the preview (issue 40). The copy is
// a band of rows per task; the page keeps the job it had, the worker gets the copy.

import type { PrintJob } from '../protocol/job-types';

/** The rows a task copies at most, in cells: a few ms of the page's thread on a busy machine. */
const BAND_CELLS = 4 << 20;

/** The job with its rows in one fresh buffer, and that buffer for `postMessage`'s transfer list; `pause` lets the page run between bands. */
export async function jobForTransfer(job: PrintJob, pause: () => Promise<unknown>): Promise<{ job: PrintJob; transfer: ArrayBuffer[] }> {
  const { cols, rows } = job.grid;
  const cells = new Uint8Array(cols * rows);
  const band = Math.max(1, Math.floor(BAND_CELLS / Math.max(1, cols)));
  for (let y = 0; y < rows; y++) {
    if (y > 0 && y % band === 0) await pause();
    cells.set(job.gridData[y], y * cols);
  }
  const gridData = Array.from({ length: rows }, (_, y) => cells.subarray(y * cols, (y + 1) * cols));
  return { job: { ...job, gridData }, transfer: [cells.buffer] };
}
