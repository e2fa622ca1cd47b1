// Plans a job by its strategy: stop and fire (planner.ts), or exposure on the move (scan.ts) seen
// through the same Plan, one "stop" per pass, so progress, estimates and checkpoints count passes.

import type { JobHeader, StrategyName } from '../protocol/job-types';
import { planJob, type Plan, type PlannerJob } from './planner';
import { passSpanUs, planScan, type ScanPlan } from './scan';
import type { Machine } from './time-model';

export interface JobPlan {
  plan: Plan;
  /** Set for a scan job: its passes, their switch times and its motion. */
  scan: ScanPlan | null;
}

export function planAnyJob(job: PlannerJob, machine: Machine): JobPlan {
  if (job.header.strategy !== 'scan') return { plan: planJob(job, machine), scan: null };
  const scan = planScan(job, machine);
  return { plan: scanAsPlan(scan, machine, job.header), scan };
}

/** A scan plan as a Plan of one entry per pass (at its first head column), with no stop durations. */
export function scanAsPlan(scan: ScanPlan, machine: Machine, h: Pick<JobHeader, 'originUm' | 'pitchUm'>): Plan {
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

/** The orders the automatic choice weighs, in the order it prefers them on a tie. */
export const ORDERS: StrategyName[] = ['scan', 'serpentine', 'shortest', 'raster', 'random'];

/**
 * Each order's estimate for the job, µs: what the Mega's planner will count for it. An order that
 * cannot plan a job that has light (a scan pass over the 32-bit limit) is Infinity.
 */
export function orderEstimates(job: PlannerJob, machine: Machine, bedXUm = Infinity): Record<StrategyName, number> {
  const out = {} as Record<StrategyName, number>;
  let lit = false;
  // A scan's strokes run up and out beyond the artwork: one that leaves the bed is no choice.
  const strokeUm = (steps: number) => (steps * 1_000_000) / machine.stepsMilli[0];
  for (const name of ORDERS) {
    const { plan, scan } = planAnyJob({ ...job, header: { ...job.header, strategy: name } }, machine);
    const offBed = scan?.passes.some((p) => strokeUm(p.startSteps) < 0 || strokeUm(p.stopSteps) > bedXUm) ?? false;
    out[name] = offBed ? Infinity : plan.count || !lit ? plan.estimateUs : Infinity;
    if (name !== 'scan' && plan.count) lit = true;
  }
  if (lit && out.scan === 0) out.scan = Infinity;
  return out;
}

/** The fastest order of `estimates`; on a tie, the first in ORDERS. */
export function fastestOrder(estimates: Record<StrategyName, number>): StrategyName {
  return ORDERS.reduce((best, name) => (estimates[name] < estimates[best] ? name : best), ORDERS[0]);
}
