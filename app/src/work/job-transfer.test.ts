import { describe, expect, it } from 'vitest';
import { testPattern } from '../device/test-pattern';
import { DoseGrid } from '../studio/grid/grid';
import { DEFAULT_EXPOSURE, jobFromGrid } from '../studio/grid-job';
import { DEFAULT_BED } from '../studio/editor.svelte';
import { jobForTransfer } from './job-transfer';

describe('a job handed to the work worker', () => {
  it('carries the same rows in one buffer of its own, a band of rows per task, the page\'s job untouched', async () => {
    const grid = new DoseGrid(4000, 4000);
    for (let y = 0; y < 4000; y += 7) grid.cells.fill(y % 255, y * 4000 + 3, y * 4000 + 3997);
    const job = jobFromGrid(grid, DEFAULT_BED, DEFAULT_EXPOSURE)!;
    let pauses = 0;
    const sent = await jobForTransfer(job, async () => pauses++);
    expect(pauses).toBe(3); // 16 M cells in bands of about 4 M
    expect(sent.transfer).toHaveLength(1);
    expect(sent.transfer[0].byteLength).toBe(job.grid.cols * job.grid.rows);
    expect(sent.job.grid).toEqual(job.grid);
    expect(sent.job.gridData.every((row, y) => Buffer.compare(row as Uint8Array, job.gridData[y] as Uint8Array) === 0)).toBe(true);
    expect(sent.job.gridData.every((row) => (row as Uint8Array).buffer === sent.transfer[0])).toBe(true);
    structuredClone(sent.job, { transfer: sent.transfer }); // moved away: the page's own cells are not
    expect(sent.transfer[0].byteLength).toBe(0);
    expect(grid.cells[7 * 4000 + 3]).toBe(7);
  });

  it('takes rows that are plain arrays, as the test pattern\'s are', async () => {
    const job = testPattern(4000);
    const sent = await jobForTransfer(job, async () => {});
    expect(sent.job.gridData.map((r) => Array.from(r))).toEqual(job.gridData.map((r) => Array.from(r)));
  });
});
