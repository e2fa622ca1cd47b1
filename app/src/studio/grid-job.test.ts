import { describe, expect, it } from 'vitest';
import { DoseGrid } from './grid/grid';
import { History } from './grid/history';
import { rectangle } from './grid/tools';
import { DEFAULT_EXPOSURE, jobFromGrid } from './grid-job';

describe('a drawing as a job', () => {
  it('is cropped to what has a dose and placed where it lies on the bed', () => {
    const g = new DoseGrid(100, 80);
    const machine = { bedMm: { x: 5, y: 4 }, pitchUm: { x: 50, y: 50 } };
    expect(jobFromGrid(g, machine, DEFAULT_EXPOSURE)).toBeNull();
    const e = new History(g).begin('r');
    rectangle(g, e, 10, 20, 19, 24, true, 1, 200);
    const job = jobFromGrid(g, machine, DEFAULT_EXPOSURE)!;
    expect(job.grid).toEqual({ cols: 10, rows: 5 });
    expect(job.originUm).toEqual({ x: 500, y: 1000 });
    expect(Array.from(job.gridData[0])).toEqual(new Array(10).fill(200));
  });
});
