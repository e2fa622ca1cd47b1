// What the work worker does for the preview's plan: the plan as the Mega will make it, its clock and
// each LED's share. Apart from the worker's message plumbing, so it is tested in Node.

import { headerOf } from '../planner/job-header';
import { fastestOrder, orderEstimates, planAnyJob } from '../planner/job-plan';
import { ledCoverage, timeline } from './exposure-preview';
import type { Plan } from '../planner/plan';
import type { MotionModel } from '../planner/time-model';
import type { PrintJob, StrategyName } from '../protocol/job-types';
import { mixedWords } from '../job/scan-words';
import { mixedPreview, mixedTimeline } from './mixed-preview';
import { scanCoverage, scanPreview, scanTimeline, type ScanPreview } from './scan-preview';

export interface Planned {
  plan: Plan;
  /** The time model's clock after each stop, µs. */
  clock: Float64Array;
  /** Cells each LED exposes. */
  coverage: number[];
  /** A scan job's passes and light from its switch times (the plan then counts passes); null for stops. */
  scan: ScanPreview | null;
  /** A mixed job's words for its passes (planner.md "Mixed mode"), drawn as `scan`; null for the others. */
  mixed: string | null;
  /** Every order's estimate for the drawing, µs (job-plan.ts orderEstimates), and the order planned. */
  orders: Record<StrategyName, number>;
  order: StrategyName;
}

export type PlanRequest = { job: PrintJob; machine: MotionModel; auto?: boolean; bedXUm?: number };

/**
 * The plan for `asked`, in its fastest order when `auto`; it throws what the planner throws.
 * `bedXUm`: the bed's width, which an automatic order's scan strokes must stay within.
 */
export function planJob({ job: asked, machine, auto, bedXUm }: PlanRequest): Planned {
  const orders = orderEstimates({ header: headerOf(asked), cells: asked.gridData }, machine, bedXUm);
  const order = auto ? fastestOrder(orders) : asked.strategy.name;
  const job = { ...asked, strategy: { ...asked.strategy, name: order } };
  const { plan, scan, mixed } = planAnyJob({ header: headerOf(job), cells: job.gridData }, machine);
  if (mixed) {
    // Drawn pass by pass as a scan job is, each pass marked on the move or stop by stop.
    const preview = mixedPreview(job, mixed);
    const passes = { ...plan, count: preview.lines.length, hx: Int32Array.from(preview.lines, (l) => Math.round(l.fromCol)), hy: Int32Array.from(preview.lines, (l) => l.row) };
    return { plan: passes, clock: mixedTimeline(mixed), coverage: scanCoverage(preview.doses), scan: preview, mixed: mixedWords(mixed), orders, order };
  }
  if (scan) {
    const preview = scanPreview(job, scan);
    return { plan, clock: scanTimeline(job, scan, machine), coverage: scanCoverage(preview.doses), scan: preview, mixed: null, orders, order };
  }
  return { plan, clock: timeline(job, plan, machine), coverage: ledCoverage(plan), scan: null, mixed: null, orders, order };
}
