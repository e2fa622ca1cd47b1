// What the planning worker does with one request: the plan as the Mega will make it, its clock and
// each LED's share. Apart from the worker's message plumbing, so it is tested in Node.

import { headerOf } from '../planner/job-header';
import { fastestOrder, orderEstimates, planAnyJob } from '../planner/job-plan';
import { ledCoverage, timeline } from './exposure-preview';
import type { PlanReply, PlanRequest } from './plan-client';
import { scanCoverage, scanPreview, scanTimeline } from './scan-preview';

export function planReply({ id, job: asked, machine, auto, bedXUm }: PlanRequest): PlanReply {
  try {
    const orders = orderEstimates({ header: headerOf(asked), cells: asked.gridData }, machine, bedXUm);
    const order = auto ? fastestOrder(orders) : asked.strategy.name;
    const job = { ...asked, strategy: { ...asked.strategy, name: order } };
    const { plan, scan } = planAnyJob({ header: headerOf(job), cells: job.gridData }, machine);
    if (scan) {
      const preview = scanPreview(job, scan);
      return { id, planned: { plan, clock: scanTimeline(job, scan, machine), coverage: scanCoverage(preview.doses), scan: preview, orders, order } };
    }
    return { id, planned: { plan, clock: timeline(job, plan, machine), coverage: ledCoverage(plan), scan: null, orders, order } };
  } catch (e) {
    return { id, error: (e as Error).message };
  }
}
