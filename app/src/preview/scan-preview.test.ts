import { describe, expect, it } from 'vitest';
import { durationTables } from '../planner/dose';
import { headerOf } from '../planner/job-header';
import { planScan } from '../planner/planner-wasm';
import type { PrintJob } from '../protocol/job-types';
import { motionOf } from '../studio/machine-config';
import { DEFAULT_CONFIG } from '../studio/machine-config';
import { scanCoverage, scanPreview, scanPreviewGrid, scanTimeline } from './scan-preview';

function board(fullUs: number): PrintJob {
  const cols = 40, rows = 11;
  const grid = Array.from({ length: rows }, (_, y) => Array.from({ length: cols }, (_, x) => (x === 5 || y === 3 ? 255 : x > 30 && x < 34 ? 90 : (x * y) % 17 === 0 ? 1 : 0)));
  grid[9] = grid[9].map((_, x) => (x < 3 || x > 36 ? 255 : 0)); // a stretch the head flies over
  return {
    grid: { cols, rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 20000, y: 20000 },
    dose: { map: 'linear', fullUs }, leds: { offsets: [[0, 0], [1, 1], [0, 2], [-1, 3]] },
    strategy: { name: 'scan' }, gridData: grid,
  };
}

describe('scan preview', () => {
  it.each([4000, 40])("gives each cell the on-time its LED's switch times give it, which is the dose it asks for (full %i µs)", (fullUs) => {
    const job = board(fullUs);
    const header = headerOf(job);
    const scan = planScan({ header, cells: job.gridData }, motionOf(DEFAULT_CONFIG));
    // Slow for its dose, the head flies blank stretches; at the capped speed (40 µs) it crosses them.
    expect(scan.passes.some((p) => p.jumps.length > 0)).toBe(fullUs === 4000);
    const { doses, lines } = scanPreview(job, scan);
    const tables = durationTables(header);
    const got = new Map<string, number>();
    for (let i = 0; i < doses.cell.length; i++) got.set(`${doses.led[i]}:${doses.cell[i]}`, (got.get(`${doses.led[i]}:${doses.cell[i]}`) ?? 0) + doses.us[i]);
    const want = new Map<string, number>();
    scan.passes.forEach((p) => job.leds.offsets.forEach(([, dy], k) => {
      const row = p.hy + dy;
      if (row < 0 || row >= job.grid.rows) return;
      Array.from(job.gridData[row]).forEach((v, col) => tables[k][v] && want.set(`${k}:${row * job.grid.cols + col}`, tables[k][v]));
    }));
    expect(got).toEqual(want);
    expect(lines.map((l) => l.descending)).toEqual(scan.passes.map((_, i) => i % 2 === 1));
    lines.forEach((l) => expect(l.descending ? l.fromCol > l.toCol : l.fromCol < l.toCol).toBe(true));
    expect(scanCoverage(doses).reduce((a, b) => a + b)).toBe(want.size);
  });

  it('scrubs pass by pass, and its clock ends at the estimate', () => {
    const job = board(4000);
    const machine = motionOf(DEFAULT_CONFIG);
    const scan = planScan({ header: headerOf(job), cells: job.gridData }, machine);
    const { doses } = scanPreview(job, scan);
    const lit = (upTo: number) => scanPreviewGrid(job, doses, upTo).doseUs.filter((d) => d > 0).length;
    expect(lit(0)).toBe(0);
    expect(lit(1)).toBeGreaterThan(0);
    expect(lit(1)).toBeLessThan(lit(scan.passes.length));
    const clock = scanTimeline(job, scan, machine);
    expect(clock.at(-1)).toBe(scan.estimateUs);
  });
});
