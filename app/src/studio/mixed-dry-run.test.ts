// The dry run of a mixed job (planner.md "Mixed mode"): it says which passes run on the move, holds
// their strokes against the bed, and plays the plan's own times through the head's heat model; and
// the simulated printer runs it, a band of stops too, in the steps and time the app plans.

import { describe, expect, it } from 'vitest';
import { GEOMETRIES } from '../planner/test-jobs';
import { headerOf } from '../planner/job-header';
import { planMixed } from '../planner/planner-wasm';
import { encodeJob } from '../protocol/job-encode';
import type { PrintJob } from '../protocol/job-types';
import { CONFIG_DEFAULTS, motionOf } from '../machine/config';
import { SimHost } from '../sim/sim-host.fixture';
import { dryRun } from './dry-run';
import { DEFAULT_CONFIG, limitsOf } from './machine-config';
import { forecastMixedThermal } from './thermal-forecast';

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

describe('a mixed job on the simulated printer (the firmware itself)', () => {
  it('runs from the card step by step, in the forecast time (2 %) and heat (2 °C)', () => {
    const j = job(20_000);
    j.dose = { map: 'threshold', level: 128, fullUs: 20_000 }; // 20 ms a cell: the LEDs' heat shows
    const h = new SimHost();
    h.cmd('G28');
    h.upload('M.UVJ', encodeJob(j));
    h.cmd('M23 M.UVJ');
    h.sim.advance(3000); // the Mega measures the Nano's clock (W) before a pass on the move
    const startC = h.sim.thermal.temp.slice();
    h.sim.thermal.resetPeak();
    const from = h.sim.clock.now;
    h.cmd('M24');
    const end = h.waitFor(/^JOB:(done|paused|failed)/, 3_600_000);
    const us = h.sim.clock.now - from;
    const header = headerOf(j), machine = motionOf(CONFIG_DEFAULTS, [0, 0]);
    const mixed = planMixed({ header, cells: j.gridData }, machine);
    expect(mixed.passes.some((p) => p.scan) && mixed.passes.some((p) => !p.scan)).toBe(true);
    expect(end).toMatch(new RegExp(`^JOB:done file=M.UVJ stop=${mixed.steps}/${mixed.steps}`));
    const run = forecastMixedThermal(mixed, header, machine, { limitsC: limitsOf(CONFIG_DEFAULTS), startC, paced: false });
    expect(run.pause).toBeNull();
    expect(run.totalUs).toBe(mixed.estimateUs);
    console.log(`[mixed sim] ${mixed.passes.filter((p) => p.scan).length} of ${mixed.passes.length} passes on the move, ${mixed.steps} steps: estimate ${(mixed.estimateUs / 1e6).toFixed(2)} s, the simulated printer ${(us / 1e6).toFixed(2)} s`);
    expect(Math.abs(us - run.totalUs) / run.totalUs).toBeLessThan(0.02);
    for (let i = 0; i < 6; i++) expect(Math.abs(run.peakC[i] - h.sim.thermal.peak[i]), `T${i}`).toBeLessThanOrEqual(2);
  });

  it('runs a band of stops from the card, counted and timed as the app plans it', () => {
    // The job above, then 8 passes of one cell near either end of every other row: a band of stops (planner.md "Bands").
    const j = job(20_000);
    j.grid = { cols: 80, rows: 64 };
    j.gridData = [...j.gridData, ...Array.from({ length: 32 }, (_, y) => Array.from({ length: 80 }, (_, x) => (y % 2 === 0 && x === (y % 4 ? 2 : 77) ? 255 : 0)))];
    const header = headerOf(j), machine = motionOf(CONFIG_DEFAULTS, [0, 0]);
    const mixed = planMixed({ header, cells: j.gridData }, machine);
    expect(mixed.passes.map((p) => (p.scan ? 's' : p.band ? `b${p.band}` : 'x')).join('')).toMatch(/^[sx]{8}b8$/);
    const h = new SimHost();
    h.cmd('G28');
    h.upload('B.UVJ', encodeJob(j));
    h.cmd('M23 B.UVJ');
    h.sim.advance(3000);
    const from = h.sim.clock.now;
    h.cmd('M24');
    const end = h.waitFor(/^JOB:(done|paused|failed)/, 3_600_000);
    const us = h.sim.clock.now - from;
    expect(end).toMatch(new RegExp(`^JOB:done file=B.UVJ stop=${mixed.steps}/${mixed.steps}`));
    console.log(`[mixed sim] a band of stops: ${mixed.steps} steps, estimate ${(mixed.estimateUs / 1e6).toFixed(2)} s, the simulated printer ${(us / 1e6).toFixed(2)} s`);
    expect(Math.abs(us - mixed.estimateUs) / mixed.estimateUs).toBeLessThan(0.02);
  });
});
