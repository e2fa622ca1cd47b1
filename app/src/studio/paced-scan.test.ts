// Paced scan and mixed jobs (issue 41 item 1): the Mega waits to cool between passes, before the
// move to the next, and the forecast plays that same wait. On the simulated printer (the firmware
// itself) a paced job that would pause unpaced never pauses, and takes the forecast time within 2 %.

import { describe, expect, it } from 'vitest';
import { headerOf } from '../planner/job-header';
import { planMixed } from '../planner/planner-wasm';
import { planScan } from '../planner/planner-wasm';
import { encodeJob } from '../protocol/job-encode';
import type { PrintJob } from '../protocol/job-types';
import { CONFIG_DEFAULTS, motionOf } from '../machine/config';
import { cooledUs, SimHost } from '../sim/sim-host.fixture';
import { blockJob } from './block-job.fixture';
import { limitsOf } from './machine-config';
import { forecastMixedThermal, forecastScanThermal, type ThermalRun } from './thermal-forecast';

function simulate(job: PrintJob, paced: boolean) {
  const h = new SimHost();
  h.cmd('G28');
  h.upload('P.UVJ', encodeJob(job));
  h.cmd('M23 P.UVJ');
  h.sim.advance(3000); // the Mega measures the Nano's clock (W) before a pass on the move
  const startC = h.sim.thermal.temp.slice();
  h.sim.thermal.resetPeak();
  const from = h.sim.clock.now;
  h.cmd(paced ? 'M24 P1' : 'M24');
  const end = h.waitFor(/^JOB:(done|paused|failed)/, 3_600_000);
  return { startC, end, peakC: h.sim.thermal.peak.slice(), us: h.sim.clock.now - from, cooledUs: cooledUs(h) };
}

type Forecast = (job: PrintJob, startC: number[], paced: boolean) => ThermalRun;
const machine = motionOf(CONFIG_DEFAULTS, [0, 0]);
const scanForecast: Forecast = (job, startC, paced) => {
  const header = headerOf(job);
  return forecastScanThermal(planScan({ header, cells: job.gridData }, machine), header, machine, { limitsC: limitsOf(CONFIG_DEFAULTS), startC, paced });
};
const mixedForecast: Forecast = (job, startC, paced) => {
  const header = headerOf(job);
  const mixed = planMixed({ header, cells: job.gridData }, machine);
  expect(mixed.passes.some((p) => p.scan) && mixed.passes.some((p) => !p.scan)).toBe(true);
  return forecastMixedThermal(mixed, header, machine, { limitsC: limitsOf(CONFIG_DEFAULTS), startC, paced });
};

// A filled block, 20 mm of passes at 50 µm: hot enough to pause unpaced. The mixed job's sparse
// bands (one cell in four rows) make passes of stops between the passes on the move.
const scanJob = (): PrintJob => blockJob(4, 1, 400, 300, { seed: 3, strategy: 'scan', gray: false });
const mixedJob = (): PrintJob => {
  const j = blockJob(4, 1, 400, 300, { seed: 3, strategy: 'mixed', gray: false });
  j.gridData = j.gridData.map((row, y) => ((y >> 2) % 8 === 7 ? Array.from(row, (v, x) => (y % 4 === 0 && x === (y * 37) % 400 ? v : 0)) : row));
  return j;
};

describe('a paced job on the move, on the simulated printer', () => {
  const orders: [string, () => PrintJob, Forecast][] = [['scan', scanJob, scanForecast], ['mixed', mixedJob, mixedForecast]];
  for (const [order, make, forecast] of orders) it(`${order}: unpaced it pauses where forecast; paced it never pauses and takes the forecast time (2 %)`, () => {
    const job = make();
    const plain = simulate(job, false);
    const plainRun = forecast(job, plain.startC, false);
    expect(plain.end).toMatch(/^JOB:paused .*reason=overtemp/);
    expect(plainRun.pause).not.toBeNull();

    const sim = simulate(job, true);
    const run = forecast(job, sim.startC, true);
    console.log(`[paced ${order}] forecast ${(run.totalUs / 1e6).toFixed(2)} s (${(run.waitUs / 1e6).toFixed(2)} s cooling), the simulated printer ${(sim.us / 1e6).toFixed(2)} s (${(sim.cooledUs / 1e6).toFixed(2)} s cooling)`);
    expect(sim.end).toMatch(/^JOB:done .*paced=1/);
    expect(run.pause).toBeNull();
    expect(run.waitUs).toBeGreaterThan(0);
    const limits = limitsOf(CONFIG_DEFAULTS);
    for (let i = 0; i < 6; i++) expect(sim.peakC[i], `T${i}`).toBeLessThan(limits[i]);
    expect(Math.abs(sim.us - run.totalUs) / run.totalUs).toBeLessThan(0.02);
    expect(Math.abs(sim.cooledUs - run.waitUs) / run.totalUs).toBeLessThan(0.02);
  }, 60_000);
});
