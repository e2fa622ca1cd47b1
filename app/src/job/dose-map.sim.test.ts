// The delivered-dose map against the firmware itself (the simulated printer, its C++ as WebAssembly):
// a scan job's programs and a resumed stop job's stops, as the Mega reports them, land on their cells.
import { describe, expect, it } from 'vitest';

import { DoseLedger } from '../device/dose-ledger';
import { parseReply } from '../protocol/dialect-reply';
import { encodeJob } from '../protocol/job-encode';
import type { PrintJob } from '../protocol/job-types';
import { SimHost } from '../sim/sim-host.fixture';
import { DEFAULT_CONFIG, motionOf } from '../studio/machine-config';
import { deliveredMap } from './dose-map';
import { planDoses, programCount, recordOf } from './dose-plan';
import { headerOf } from '../planner/job-header';
import { planAnyJob } from '../planner/job-plan';

/** The link speed the simulated Mega plans at (its M115 says Cap:LINK_BAUD:250000). */
const machine = motionOf(DEFAULT_CONFIG, [0, 0], 250_000);

function comb(strategy: PrintJob['strategy']['name'], rows = 8): PrintJob {
  const cols = 70;
  return {
    grid: { cols, rows }, pitchUm: { x: 100, y: 100 }, originUm: { x: 20000, y: 20000 },
    dose: { map: 'linear', fullUs: 3000 }, leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: strategy },
    gridData: Array.from({ length: rows }, (_, y) => Array.from({ length: cols }, (_, x) => ((x + y) % 2 ? 255 : x % 5 === 0 ? 100 : 0))),
  };
}

function start(h: SimHost, job: PrintJob): void {
  h.cmd('G28');
  h.cmd('M28 D.UVJ');
  for (const record of encodeJob(job, 2).trimEnd().split('\n')) h.cmd(record);
  h.cmd('M29');
  h.cmd('M23 D.UVJ');
  h.cmd('M24');
}

function ledgerOf(lines: string[]): DoseLedger {
  const l = new DoseLedger();
  for (const line of lines) {
    const r = parseReply(line);
    if (r?.kind === 'dose') l.add(r);
  }
  return l;
}

const lit = (job: PrintJob) => job.gridData.flatMap((row) => Array.from(row)).filter((v) => v > 0).length;

describe('delivered-dose map on the simulated printer', () => {
  it("counts a scan job's cells from its programs' records, each within 2 %", () => {
    const job = comb('scan');
    const plan = planDoses(job, machine);
    expect(Array.from({ length: plan.steps }, (_, s) => programCount(plan, s)).some((n) => n > 1)).toBe(true); // passes of more than 64 events
    const h = new SimHost();
    start(h, job);
    h.waitFor(/^JOB:done/);
    expect(h.lines.filter((l) => /^DOSE:stop=\d+ prog=[1-9]/.test(l)).length).toBeGreaterThan(0);
    const m = deliveredMap(plan, ledgerOf(h.lines));
    expect(m.counts).toEqual({ within: lit(job), off: 0, dark: 0, waiting: 0, twice: 0 });
    expect(m.worst).toBeLessThan(0.02);
  });

  it("counts a mixed job's passes on the move and its stops alike", () => {
    const job = comb('mixed', 12);
    job.gridData = job.gridData.map((row, y) => (y >= 8 ? Array.from(row, (_, x) => (y === 9 && x === 37 ? 255 : 0)) : row)); // one cell in a band: a stop
    const plan = planDoses(job, machine);
    const mixed = planAnyJob({ header: headerOf(job), cells: job.gridData }, machine).mixed!;
    expect(new Set(mixed.passes.map((p) => p.scan))).toEqual(new Set([true, false])); // passes on the move, and stops
    const h = new SimHost();
    start(h, job);
    h.waitFor(/^JOB:done/);
    const m = deliveredMap(plan, ledgerOf(h.lines));
    expect(m.counts).toEqual({ within: lit(job), off: 0, dark: 0, waiting: 0, twice: 0 });
  });

  it('counts a stop job resumed after a power cycle once, and marks the stop lit again', () => {
    const job = comb('serpentine', 4);
    const plan = planDoses(job, machine);
    const h = new SimHost();
    start(h, job);
    const fires = h.sim.module.fires;
    while (h.sim.module.lit === 0 || h.sim.module.fires - fires < plan.steps / 2) h.sim.advance(1);
    h.sim.powerCycle(); // mid-stop: its light is cut, and the printhead's records with it
    h.reconnect();
    h.cmd('G28');
    h.cmd('M1000');
    h.waitFor(/^JOB:done/);
    expect(h.lines.filter((l) => /^DOSE:.* again=1$/.test(l))).toHaveLength(1);
    const m = deliveredMap(plan, ledgerOf(h.lines));
    expect(m.counts.off + m.counts.dark + m.counts.waiting).toBe(0);
    expect(m.counts.within).toBe(lit(job));
    expect(m.twiceSteps).toHaveLength(1);
    expect(m.counts.twice).toBe(recordOf(plan, m.twiceSteps[0]).cell.length);
  });
});
