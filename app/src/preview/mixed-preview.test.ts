import { describe, expect, it } from 'vitest';
import { GEOMETRIES } from '../planner/test-jobs';
import { headerOf } from '../planner/job-header';
import { planMixed } from '../planner/planner-wasm';
import type { MotionModel } from '../planner/time-model';
import type { PrintJob } from '../protocol/job-types';
import { mixedWords } from '../job/scan-words';
import { mixedPreview, mixedTimeline } from './mixed-preview';

const MACHINE: MotionModel = { vmaxUmS: [100_000, 100_000], accelUmS2: [2_000_000, 2_000_000], settleUs: 2000, overheadUs: 1500, startUm: [0, 0], stepsMilli: [80_000, 80_000], linkBaud: 115200 };

// Dense bands of four rows between bands with one dot: passes on the move and passes of stops.
const grid = Array.from({ length: 32 }, (_, y) => Array.from({ length: 80 }, (_, x) => ((y >> 2) % 2 === 0 ? 200 : y % 4 === 1 && x === (y * 37) % 80 ? 255 : 0)));
const job: PrintJob = {
  grid: { cols: 80, rows: 32 }, pitchUm: { x: 50, y: 50 }, originUm: { x: 5000, y: 5000 }, dose: { map: 'linear', fullUs: 4000 },
  leds: { offsets: GEOMETRIES.adjacent }, strategy: { name: 'mixed' },
  gridData: grid,
};

describe('the preview of a mixed job', () => {
  const mixed = planMixed({ header: headerOf(job), cells: job.gridData }, MACHINE);
  const preview = mixedPreview(job, mixed);

  it('marks which passes scan: a line for a pass on the move, its stops for the others', () => {
    expect(preview.lines).toHaveLength(mixed.passes.length);
    preview.lines.forEach((l, i) => {
      const p = mixed.passes[i];
      expect(l.row).toBe(p.hy);
      expect(l.stops).toEqual(p.scan ? undefined : p.stops.map((s) => s[0]));
    });
    expect(preview.lines.some((l) => l.stops)).toBe(true);
    expect(preview.lines.some((l) => !l.stops)).toBe(true);
    expect(mixedWords(mixed)).toMatch(/^8 passes, \d on the move and \d stop by stop$/);
  });

  it('draws a band of stops as its passes, each row with its stops', () => {
    const dots = { ...job, grid: { cols: 300, rows: 24 }, gridData: Array.from({ length: 24 }, (_, y) => Array.from({ length: 300 }, (_, x) => (y % 5 === 0 && x === (y * 97) % 300 ? 255 : 0))) };
    const m = planMixed({ header: headerOf(dots), cells: dots.gridData }, MACHINE);
    expect(m.passes.map((p) => !p.scan && p.band)).toEqual([5]);
    const lines = mixedPreview(dots, m).lines;
    expect(lines.map((l) => [l.row, l.stops])).toEqual([0, 5, 10, 15, 20].map((y) => [y, [(y * 97) % 300]]));
    expect(mixedWords(m)).toBe('5 passes, 0 on the move and 5 stop by stop');
    expect([...mixedTimeline(m)]).toEqual(Array(5).fill(m.estimateUs));
  });

  it('gives every lit cell its dose once, from the switch times or the stops', () => {
    const got = new Map<number, number>();
    for (let i = 0; i < preview.doses.cell.length; i++) got.set(preview.doses.cell[i], (got.get(preview.doses.cell[i]) ?? 0) + preview.doses.us[i]);
    let lit = 0;
    grid.forEach((row, y) => row.forEach((v, x) => {
      if (!v) return;
      lit++;
      expect(got.get(y * 80 + x), `cell ${x},${y}`).toBeCloseTo(Math.round((4000 * v) / 255), 6);
    }));
    expect(got.size).toBe(lit);
    expect(preview.doses.from[preview.doses.from.length - 1]).toBe(preview.doses.cell.length);
  });

  it('ends its clock at the estimate', () => {
    const clock = mixedTimeline(mixed);
    expect(clock).toHaveLength(mixed.passes.length);
    expect(clock[clock.length - 1]).toBe(mixed.estimateUs);
  });
});
