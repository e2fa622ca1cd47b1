// What the planning worker does with one request: the plan as the Mega will make it, its clock and
// each LED's share. Apart from the worker's message plumbing, so it is tested in Node.

import { headerOf } from '../planner/job-header';
import { fastestOrder, orderEstimates, planAnyJob } from '../planner/job-plan';
import { ledCoverage, timeline } from './exposure-preview';
import type { PlanReply, PlanRequest } from './plan-client';
import { mixedWords } from '../job/scan-words';
import { mixedPreview, mixedTimeline } from './mixed-preview';
import { scanCoverage, scanPreview, scanTimeline } from './scan-preview';

export function planReply({ id, job: asked, machine, auto, bedXUm }: PlanRequest): PlanReply {
  try {
    const orders = orderEstimates({ header: headerOf(asked), cells: asked.gridData }, machine, bedXUm);
    const order = auto ? fastestOrder(orders) : asked.strategy.name;
    const job = { ...asked, strategy: { ...asked.strategy, name: order } };
    const { plan, scan, mixed } = planAnyJob({ header: headerOf(job), cells: job.gridData }, machine);
    if (mixed) {
      // Drawn pass by pass as a scan job is, each pass marked on the move or stop by stop.
      const preview = mixedPreview(job, mixed);
      const passes = { ...plan, count: mixed.passes.length, hx: Int32Array.from(preview.lines, (l) => Math.round(l.fromCol)), hy: Int32Array.from(mixed.passes, (p) => p.hy) };
      return { id, planned: { plan: passes, clock: mixedTimeline(mixed), coverage: scanCoverage(preview.doses), scan: preview, mixed: mixedWords(mixed), orders, order } };
    }
    if (scan) {
      const preview = scanPreview(job, scan);
      return { id, planned: { plan, clock: scanTimeline(job, scan, machine), coverage: scanCoverage(preview.doses), scan: preview, mixed: null, orders, order } };
    }
    return { id, planned: { plan, clock: timeline(job, plan, machine), coverage: ledCoverage(plan), scan: null, mixed: null, orders, order } };
  } catch (e) {
    return { id, error: (e as Error).message };
  }
}
