// The planning worker: plans each job the preview asks for off the page's thread (plan-client.ts).

import { planReply } from './plan-work';
import type { PlanRequest } from './plan-client';

onmessage = (e: MessageEvent<PlanRequest>) => {
  const reply = planReply(e.data);
  const transfer = 'planned' in reply ? [reply.planned.plan.hx.buffer, reply.planned.plan.hy.buffer, reply.planned.plan.durations.buffer, reply.planned.clock.buffer] : [];
  postMessage(reply, { transfer });
};
