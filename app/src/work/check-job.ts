// The dry run before an exposure, in its own work worker (loaded on demand by the job control):
// a whole bed's plan and heat forecast take seconds, and the page stays live, shows how far it
// has got and can cancel it.

import type { CallOptions } from './work-client';
import { spawnWorker, WorkClient } from './work-client';
import type { DryRunSummary, WorkRequest } from './work-types';

const checks = new WorkClient(spawnWorker, 600_000);

export const checkJob = (request: Omit<Extract<WorkRequest, { kind: 'dry-run' }>, 'kind'>, opts?: CallOptions): Promise<DryRunSummary> =>
  checks.call<DryRunSummary>({ kind: 'dry-run', ...request }, opts);

export { Cancelled } from './work-client';
