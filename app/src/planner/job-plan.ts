// Plans a job by its strategy: stop and fire, or exposure on the move seen through the same Plan,
// one "stop" per pass, so progress, estimates and checkpoints count passes. The plans are the
// Mega's own: its C++ planners as WebAssembly (planner-wasm.ts), loaded by the work worker, where
// every plan of the app is made (work/answer.ts).

import type { JobHeader, StrategyName } from '../protocol/job-types';
import { mixedPassCount, passSpanUs, type MixedPlan, type Plan, type PlannerJob, type ScanPass, type ScanPlan } from './plan';
import { ORDERS, planJob, planMixed, planScan } from './planner-wasm';
import type { MotionModel } from './time-model';

export { ORDERS, orderEstimates } from './planner-wasm';

export interface JobPlan {
  /** One entry per step of the job's progress, as the Mega counts it: a stop, or a pass on the move. */
  plan: Plan;
  /** Set for a scan job: its passes, their switch times and its motion. */
  scan: ScanPlan | null;
  /** Set for a mixed job: each pass on the move or stop by stop (planner.md "Mixed mode"). */
  mixed: MixedPlan | null;
}

export function planAnyJob(job: PlannerJob, machine: MotionModel): JobPlan {
  if (job.header.strategy === 'mixed') {
    const mixed = planMixed(job, machine);
    return { plan: mixedAsPlan(mixed, machine, job.header), scan: null, mixed };
  }
  if (job.header.strategy !== 'scan') return { plan: planJob(job, machine), scan: null, mixed: null };
  const scan = planScan(job, machine);
  return { plan: scanAsPlan(scan, machine, job.header), scan, mixed: null };
}

/**
 * A mixed plan as a Plan of the Mega's progress steps: each stop with its durations, each pass on the
 * move as one entry at its first head column with none; `passes` counts every pass, a band's each.
 */
export function mixedAsPlan(mixed: MixedPlan, machine: MotionModel, h: Pick<JobHeader, 'originUm' | 'pitchUm'>): Plan {
  const n = mixed.steps;
  const plan: Plan = { count: n, hx: new Int32Array(n), hy: new Int32Array(n), durations: new Uint32Array(4 * n), passes: mixedPassCount(mixed), estimateUs: mixed.estimateUs, travelUm: [0, 0] };
  let i = 0, x = machine.startUm[0], y = machine.startUm[1];
  const go = (toX: number, toY: number) => {
    plan.travelUm[0] += Math.abs(toX - x);
    plan.travelUm[1] += Math.abs(toY - y);
    x = toX;
    y = toY;
  };
  for (const p of mixed.passes) {
    const py = h.originUm[1] + p.hy * h.pitchUm[1];
    if (p.scan) {
      plan.hx[i] = p.pass.descending ? p.pass.last : p.pass.first;
      plan.hy[i++] = p.hy;
      go(p.pass.runUpUm, py);
      go(p.pass.runOutUm, py);
      continue;
    }
    for (const [hx, hy, ...us] of p.stops) {
      plan.hx[i] = hx;
      plan.hy[i] = hy;
      plan.durations.set(us, 4 * i++);
      go(h.originUm[0] + hx * h.pitchUm[0], h.originUm[1] + hy * h.pitchUm[1]); // a band's stops change rows
    }
  }
  return plan;
}

/** A scan plan as a Plan of one entry per pass (at its first head column), with no stop durations. */
export function scanAsPlan(scan: ScanPlan, machine: MotionModel, h: Pick<JobHeader, 'originUm' | 'pitchUm'>): Plan {
  const n = scan.passes.length;
  const travel: [number, number] = [0, 0];
  let x = machine.startUm[0], y = machine.startUm[1];
  for (const p of scan.passes) {
    travel[0] += Math.abs(p.runUpUm - x) + Math.abs(p.runOutUm - p.runUpUm);
    x = p.runOutUm;
    const py = h.originUm[1] + p.hy * h.pitchUm[1];
    travel[1] += Math.abs(py - y);
    y = py;
  }
  return {
    count: n,
    hx: Int32Array.from(scan.passes, (p) => (p.descending ? p.last : p.first)),
    hy: Int32Array.from(scan.passes, (p) => p.hy),
    durations: new Uint32Array(4 * n),
    passes: n,
    estimateUs: scan.estimateUs,
    travelUm: travel,
  };
}

/** A pass's time from its start at rest to its end at rest: accelerate, the windows and flown stretches, brake (at the pass's own window). */
export function passDurationUs(_scan: ScanPlan, pass: ScanPlan['passes'][number]): number {
  return passSpanUs(pass);
}

/** The LEDs' mask after each switch of a pass, in time order, µs after its start mark. */
export function passSwitches(pass: ScanPlan['passes'][number]): { atUs: number; mask: number }[] {
  return pass.events.map(([atUs, mask]) => ({ atUs, mask }));
}

/** The studio's Order list: a strategy, or the fastest of them for the job at hand. */
export type OrderChoice = StrategyName | 'auto';

/** Where a pass's stroke on the move runs along X, µm, either way along it (a pass run leftwards
 *  starts at its right end): from its start to its stop step, run-up and run-out included. */
export function strokeSpanUm(pass: ScanPass, machine: MotionModel): { minUm: number; maxUm: number } {
  const um = (steps: number) => (steps * 1_000_000) / machine.stepsMilli[0];
  return { minUm: um(Math.min(pass.startSteps, pass.stopSteps)), maxUm: um(Math.max(pass.startSteps, pass.stopSteps)) };
}

/** Whether a stroke stays on a bed `bedXUm` wide, in whole steps as the Mega holds it there
 *  (Motion::onBed: 0 to the bed's width rounded to the nearest step). */
export function strokeOnBed(pass: ScanPass, machine: MotionModel, bedXUm: number): boolean {
  if (!Number.isFinite(bedXUm)) return Math.min(pass.startSteps, pass.stopSteps) >= 0;
  const bedSteps = Math.floor((bedXUm * machine.stepsMilli[0] + 500_000) / 1_000_000);
  return Math.min(pass.startSteps, pass.stopSteps) >= 0 && Math.max(pass.startSteps, pass.stopSteps) <= bedSteps;
}

/** The fastest order of `estimates`; on a tie, the first in ORDERS. */
export function fastestOrder(estimates: Record<StrategyName, number>): StrategyName {
  return ORDERS.reduce((best, name) => (estimates[name] < estimates[best] ? name : best), ORDERS[0]);
}
