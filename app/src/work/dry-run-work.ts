// The work worker's dry run: the job in its fastest order when asked, then the check before an
// exposure (studio/dry-run.ts), answered as the question needs it: findings, duty and times.

import { headerOf } from '../planner/job-header';
import { fastestOrder, orderEstimates } from '../planner/job-plan';
import { dryRun } from '../studio/dry-run';
import { uploadSize } from '../job/upload-time';
import { bedOf, motionOf } from '../studio/machine-config';
import type { DryRunSummary, Progress, WorkRequest } from './work-types';

export function dryRunSummary(req: Extract<WorkRequest, { kind: 'dry-run' }>, report: (p: Progress) => void): DryRunSummary {
  let job = req.job;
  if (req.auto) {
    report({ stage: 'choosing the fastest order' });
    // Of the orders whose scan strokes stay on the bed.
    const orders = orderEstimates({ header: headerOf(job), cells: job.gridData }, motionOf(req.config, [0, 0], req.linkBaud), bedOf(req.config).bedMm.x * 1000);
    job = { ...job, strategy: { name: fastestOrder(orders) } };
  }
  const { findings, duty, plan, paced } = dryRun(job, req.config, { ...req.opts, linkBaud: req.linkBaud, onStage: (stage) => report({ stage }) });
  report({ stage: 'counting the upload' });
  const upload = uploadSize(job, req.jobFormat ?? 1);
  return { order: job.strategy.name, findings, duty, estimateUs: plan.estimateUs, pacedUs: paced && !paced.pause ? paced.totalUs : null, upload };
}
