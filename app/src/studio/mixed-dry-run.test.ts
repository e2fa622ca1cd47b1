// The dry run of a mixed job (planner.md "Mixed mode"): it says which passes run on the move, holds
// their strokes against the bed, and plays the plan's own times through the head's heat model.

import { describe, expect, it } from 'vitest';
import { GEOMETRIES } from '../planner/golden';
import type { PrintJob } from '../protocol/job-types';
import { dryRun } from './dry-run';
import { DEFAULT_CONFIG } from './machine-config';

// Dense bands of four rows between bands with one pad: passes on the move and passes of stops.
const job = (originX: number): PrintJob => ({
  grid: { cols: 80, rows: 32 }, pitchUm: { x: 50, y: 50 }, originUm: { x: originX, y: 20_000 }, dose: { map: 'threshold', level: 128, fullUs: 2000 },
  leds: { offsets: GEOMETRIES.adjacent }, strategy: { name: 'mixed' },
  gridData: Array.from({ length: 32 }, (_, y) => Array.from({ length: 80 }, (_, x) => ((y >> 2) % 2 === 0 ? 255 : y % 8 === 4 && x === (y * 37) % 80 ? 255 : 0))),
});

describe('dry run of a mixed job', () => {
  it('says which passes run on the move, and forecasts the heat over the plan\'s own time', () => {
    const r = dryRun(job(20_000), DEFAULT_CONFIG);
    expect(r.mixed).not.toBeNull();
    const mode = r.findings.find((f) => f.check === 'mode')!;
    expect(mode.level).toBe('ok');
    expect(mode.message).toMatch(/^mixed job: 8 passes, [1-7] on the move and [1-7] stop by stop$/);
    expect(r.plan.count).toBe(r.mixed!.steps);
    expect(r.thermal.pause).toBeNull();
    expect(r.thermal.totalUs).toBe(r.mixed!.estimateUs);
    expect(r.findings.every((f) => f.level === 'ok')).toBe(true);
  });

  it('holds the strokes of the passes on the move, not only the stops, against the bed', () => {
    // The artwork starts 0.1 mm from the bed's edge: its cells are on the bed, the strokes' run-up is not.
    const r = dryRun(job(100), DEFAULT_CONFIG);
    expect(dryRun({ ...job(100), strategy: { name: 'serpentine' } }, DEFAULT_CONFIG).findings.find((f) => f.check === 'envelope')?.level).toBe('ok');
    expect(r.mixed!.passes.some((p) => p.scan)).toBe(true);
    expect(r.findings.find((f) => f.check === 'envelope')?.level).toBe('error');
  });
});
