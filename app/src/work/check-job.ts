// The dry run before an exposure, in its own work worker (loaded on demand by the job control):
// a whole bed's plan and heat forecast take seconds, and the page stays live, shows how far it
// has got and can cancel it. The job's cells go to the worker as a copy of their own, moved rather
// than cloned (job-transfer.ts).

import type { CallOptions } from './work-client';
import { Cancelled, spawnWorker, WorkClient } from './work-client';
import { jobForTransfer } from './job-transfer';
import type { DryRunSummary, WorkRequest } from './work-types';

const checks = new WorkClient(spawnWorker, 600_000);
const nextTask = () => new Promise((r) => setTimeout(r));

export async function checkJob(request: Omit<Extract<WorkRequest, { kind: 'dry-run' }>, 'kind'>, opts: CallOptions = {}): Promise<DryRunSummary> {
  const sent = await jobForTransfer(request.job, nextTask);
  if (opts.signal?.aborted) throw new Cancelled();
  return checks.call<DryRunSummary>({ kind: 'dry-run', ...request, job: sent.job }, { ...opts, transfer: sent.transfer });
}

export { Cancelled };
