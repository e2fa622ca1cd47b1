// What the planning worker does with one request: the plan as the Mega will make it, its clock and
// each LED's share. Apart from the worker's message plumbing, so it is tested in Node.

import { headerOf } from '../planner/job-header';
import { planJob } from '../planner/planner';
import { ledCoverage, timeline } from './exposure-preview';
import type { PlanReply, PlanRequest } from './plan-client';

export function planReply({ id, job, machine }: PlanRequest): PlanReply {
  try {
    const plan = planJob({ header: headerOf(job), cells: job.gridData }, machine);
    return { id, planned: { plan, clock: timeline(job, plan, machine), coverage: ledCoverage(plan) } };
  } catch (e) {
    return { id, error: (e as Error).message };
  }
}
