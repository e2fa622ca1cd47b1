// The dry run of a scan job (exposure on the move): it says so, estimates with the scan planner,
// and forecasts the head's heat from the LEDs' real switch times, as the simulated printer then heats.

import { describe, expect, it } from 'vitest';
import { headerOf } from '../planner/job-header';
import { planScan } from '../planner/planner-wasm';
import { encodeJob } from '../protocol/job-encode';
import type { PrintJob } from '../protocol/job-types';
import { CONFIG_DEFAULTS, motionOf } from '../machine/config';
import { SimHost } from '../sim/sim-host.fixture';
import { blockJob } from './block-job.fixture';
import { dryRun } from './dry-run';
import { DEFAULT_CONFIG, limitsOf } from './machine-config';
import { forecastScanThermal } from './thermal-forecast';

const block = (fullMs: number, fill: number, cols = 24, rows = 16): PrintJob => blockJob(fullMs, fill, cols, rows, { seed: 11, strategy: 'scan', gray: true });

function simulate(job: PrintJob) {
  const h = new SimHost();
  h.cmd('G28');
  h.upload('F.UVJ', encodeJob(job));
  h.cmd('M23 F.UVJ');
  h.sim.advance(3000); // the Mega measures the Nano's clock (W) for 2 s after it answers: a scan pass waits for it
  const startC = h.sim.thermal.temp.slice();
  h.sim.thermal.resetPeak();
  const from = h.sim.clock.now;
  h.cmd('M24');
  const end = h.waitFor(/^JOB:(done|paused)/, 3_600_000);
  return { startC, end, peakC: h.sim.thermal.peak.slice(), us: h.sim.clock.now - from };
}

describe('dry run of a scan job', () => {
  it('says it is a scan job, with its passes, speed and window, and estimates with the scan planner', () => {
    const job = block(4, 0.5, 40, 12);
    const r = dryRun(job, DEFAULT_CONFIG);
    const scan = planScan({ header: headerOf(job), cells: job.gridData }, motionOf(DEFAULT_CONFIG));
    expect(r.scan).not.toBeNull();
    expect(r.plan.estimateUs).toBe(scan.estimateUs);
    expect(r.plan.count).toBe(scan.passes.length);
    const mode = r.findings.find((f) => f.check === 'mode')!;
    expect(mode.message).toBe(`scan job (on the move): ${scan.passes.length} passes at 12.5 mm/s, a 4.00 ms window per cell`);
    expect(scan.speedUmS).toBe(12500); // 50 µm in 4 ms
    // The LEDs' duty is their on-time over the job's time, from the switch times.
    const on = [0, 1, 2, 3].map((k) => scan.passes.reduce((s, p) => s + p.leds[k].reduce((a, [x, y]) => a + y - x, 0), 0));
    expect(r.duty).toEqual(on.map((us) => us / scan.estimateUs));
    expect(r.findings.every((f) => f.level !== 'error')).toBe(true);
  });

  it('judges the dose per cell: a run of full cells lights an LED without a break, and is no error', () => {
    const job = block(4000, 1, 10, 4); // 4 s a cell, 40 s a pass with the LEDs on throughout
    job.pitchUm.x = 100; // 200 steps a window at 2000 steps/mm: a 20 ms step, which the step engine runs
    const fine = { ...DEFAULT_CONFIG, 'steps_per_mm.x': '2000' };
    const r = dryRun(job, fine);
    expect(r.scan?.passes[0].leds[0][0]).toEqual([0, 8_000_000]); // two full cells, the LED on across both
    expect(r.findings.find((f) => f.check === 'dose')).toEqual({ check: 'dose', level: 'ok', message: 'the longest exposure is 4000.0 ms' });
    expect(dryRun(block(10_001, 0.5, 4, 4), DEFAULT_CONFIG).findings.find((f) => f.check === 'dose')?.level).toBe('error');
  });

  it('says why the printer cannot run a scan whose step the step engine cannot make (mega.md M29)', () => {
    // 200 ms windows at 50 µm and 80 steps/mm: a step of 50 ms, over the engine's 32.768 ms.
    const r = dryRun(block(200, 1), DEFAULT_CONFIG);
    expect(r.scan?.passes).toEqual([]);
    expect(r.findings.find((f) => f.check === 'mode')).toEqual({
      check: 'mode',
      level: 'error',
      message: "scan job (on the move): the printer cannot run it: the scan speed 0.250 mm/s (20.0 steps/s) makes a step longer than the step engine's 32.8 ms. Choose a stop-and-fire order, or a dose that makes a shorter window",
    });
  });

  it('holds the whole pass, run-up to run-out, against the bed', () => {
    const job = block(4, 1, 10, 4);
    job.originUm = { x: 0, y: 20_000 }; // the run-up lies left of X 0
    const r = dryRun(job, DEFAULT_CONFIG);
    expect(r.findings.find((f) => f.check === 'envelope')?.level).toBe('error');
  });

  // Windows the step engine runs: 100 and 120 ms at 50 µm and 80 steps/mm are steps of 25 and 30 ms
  // (its longest is 32.768 ms: a 200 ms window is refused, mega.md M29).
  it.each([[100, 1], [120, 0.5]])('forecasts the heat of a scan job at %i ms, %f lit, as the simulated printer heats (2 °C)', (fullMs, fill) => {
    const job = block(fullMs, fill);
    const sim = simulate(job);
    const header = headerOf(job);
    const machine = motionOf(CONFIG_DEFAULTS, [0, 0]);
    const scan = planScan({ header, cells: job.gridData }, machine);
    const run = forecastScanThermal(scan, header, machine, { limitsC: limitsOf(CONFIG_DEFAULTS), startC: sim.startC, paced: false });
    expect(sim.end.startsWith('JOB:paused')).toBe(run.pause !== null);
    if (run.pause) expect(Math.abs(sim.us - run.pause.atUs)).toBeLessThanOrEqual(1_000_000);
    else expect(Math.abs(sim.us - run.totalUs) / run.totalUs).toBeLessThan(0.02);
    for (let i = 0; i < 6; i++) expect(Math.abs(run.peakC[i] - sim.peakC[i]), `T${i}`).toBeLessThanOrEqual(2);
    expect(Math.max(...run.peakC.slice(0, 4))).toBeGreaterThan(30); // the LEDs' heat shows
  });
});
