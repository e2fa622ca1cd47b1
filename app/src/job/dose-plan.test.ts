// A job's dose records: every cell's planned light falls in exactly the records the Mega reports for it.
import { describe, expect, it } from 'vitest';

import { testPattern } from '../device/test-pattern';
import { headerOf } from '../planner/job-header';
import { planAnyJob } from '../planner/job-plan';
import { scanDoses } from '../preview/scan-preview';
import type { PrintJob } from '../protocol/job-types';
import { PROGRAM_EVENTS } from '../protocol/nano';
import { DEFAULT_CONFIG, motionOf } from '../studio/machine-config';
import { dosePlanOf, planDoses, programCount, programSpans, recordOf, type DosePlan } from './dose-plan';

const machine = motionOf(DEFAULT_CONFIG);

/** Alternate cells in every row: each lit cell is two events, so a row's pass runs past 64 events. */
function comb(strategy: PrintJob['strategy']['name']): PrintJob {
  const cols = 80, rows = 6;
  return {
    grid: { cols, rows }, pitchUm: { x: 100, y: 100 }, originUm: { x: 20000, y: 20000 },
    dose: { map: 'linear', fullUs: 4000 }, leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: strategy },
    gridData: Array.from({ length: rows }, (_, y) => Array.from({ length: cols }, (_, x) => ((x + y) % 2 ? 255 : x % 7 === 0 ? 128 : 0))),
  };
}

/** Each cell's light over every record of the plan. */
function perCell(plan: DosePlan): Float64Array {
  const out = new Float64Array(plan.cols * plan.rows);
  plan.cell.forEach((c, e) => (out[c] += plan.us[e]));
  return out;
}

/** Each step's records, unpacked. */
const stepsOf = (plan: DosePlan) => Array.from({ length: plan.steps }, (_, s) => Array.from({ length: programCount(plan, s) }, (_, p) => recordOf(plan, s, p)));

describe('dose plan', () => {
  it("gives a stop's one record its durations, on the cells its LEDs are over", () => {
    const job = testPattern(4000);
    const planned = planAnyJob({ header: headerOf(job), cells: job.gridData }, machine);
    const plan = dosePlanOf(job, planned);
    expect(plan.unit).toBe('stop');
    expect(plan.steps).toBe(planned.plan.count);
    stepsOf(plan).forEach((records, i) => {
      expect(records).toHaveLength(1);
      expect(records[0].ledUs).toEqual(Array.from(planned.plan.durations.subarray(4 * i, 4 * i + 4)));
    });
    // Every cell drawn gets its planned light once, and no cell left blank gets any.
    const got = perCell(plan);
    const full = 4000;
    job.gridData.forEach((row, y) => Array.from(row).forEach((v, x) => expect(got[y * job.grid.cols + x]).toBe(Math.round((full * v) / 255))));
  });

  it('cuts a pass into programs of 64 events, each from the last event of the one before', () => {
    const events: [number, number][] = Array.from({ length: 150 }, (_, i) => [10 * (i + 1), i % 2]);
    const spans = programSpans({ events });
    expect(spans).toEqual([[0, 640], [640, 1280], [1280, 1500]]);
    expect(spans).toHaveLength(Math.ceil(150 / PROGRAM_EVENTS));
  });

  it.each(['scan', 'mixed'] as const)("splits a %s job's passes by program, and the programs' light adds up to the pass's", (strategy) => {
    const job = comb(strategy);
    const planned = planAnyJob({ header: headerOf(job), cells: job.gridData }, machine);
    const plan = dosePlanOf(job, planned);
    expect(plan.steps).toBe(planned.plan.count);
    const passes = planned.scan?.passes ?? planned.mixed!.passes.flatMap((p) => (p.scan ? [p.pass] : []));
    expect(passes.some((p) => p.events.length > PROGRAM_EVENTS)).toBe(true);
    // Against the preview's light of the whole job: the same on every cell, split or not.
    const whole = new Float64Array(job.grid.cols * job.grid.rows);
    for (const p of passes) {
      const d = scanDoses(job, { passes: [p] } as Parameters<typeof scanDoses>[1]);
      d.cell.forEach((c, i) => (whole[c] += d.us[i]));
    }
    let stopLight = 0;
    if (planned.mixed) for (const p of planned.mixed.passes) if (!p.scan) for (const [hx, hy, ...us] of p.stops) us.forEach((t, k) => t && hy + k < job.grid.rows && ((whole[(hy + k) * job.grid.cols + hx] += t), (stopLight += t)));
    const got = perCell(plan);
    got.forEach((us, c) => expect(us).toBeCloseTo(whole[c], 6));
    // Each program's LED totals are its cells' light (no cell of this comb is off the grid).
    for (const records of stepsOf(plan))
      for (const r of records) {
        const sum = [0, 0, 0, 0];
        r.led.forEach((k, i) => (sum[k] += r.us[i]));
        sum.forEach((s, k) => expect(s).toBeCloseTo(r.ledUs[k], 6));
      }
    const scanned = stepsOf(plan).filter((records) => records.length > 1);
    expect(scanned.length).toBeGreaterThan(0);
    expect(stopLight > 0).toBe(strategy === 'mixed' && planned.mixed!.passes.some((p) => !p.scan));
  });

  it('plans the job in the order it ran', () => {
    expect(planDoses(testPattern(4000), machine).unit).toBe('stop');
    expect(planDoses(comb('scan'), machine).unit).toBe('pass');
  });
});
