// Asks the planning worker for a job's plan: each request carries an id, waits in a Map and is
// settled by the worker's reply or a time-out. The page never plans on its own thread, so a whole
// bed's plan does not freeze it.

import type { Plan } from '../planner/planner';
import type { Machine } from '../planner/time-model';
import type { PrintJob, StrategyName } from '../protocol/job-types';
import type { ScanPreview } from './scan-preview';

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

/** `auto`: plan the job in its fastest order, whatever its strategy says. */
export type PlanRequest = { id: number; job: PrintJob; machine: Machine; auto?: boolean; bedXUm?: number };
export type PlanReply = { id: number; planned: Planned } | { id: number; error: string };

/** What the client needs of a Worker (a test hands it a fake one). */
export interface PlanPort {
  postMessage(m: PlanRequest): void;
  onmessage: ((e: MessageEvent<PlanReply>) => void) | null;
  terminate(): void;
}

export class PlanClient {
  #next = 1;
  readonly #pending = new Map<number, { resolve: (p: Planned) => void; reject: (e: Error) => void; timer: ReturnType<typeof setTimeout> }>();

  constructor(private readonly port: PlanPort, private readonly timeoutMs = 60_000) {
    port.onmessage = (e) => this.#settle(e.data);
  }

  /** `bedXUm`: the bed's width, which an automatic order's scan strokes must stay within. */
  plan(job: PrintJob, machine: Machine, auto = false, bedXUm?: number): Promise<Planned> {
    const id = this.#next++;
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.#pending.delete(id);
        reject(new Error(`planning took over ${this.timeoutMs / 1000} s`));
      }, this.timeoutMs);
      this.#pending.set(id, { resolve, reject, timer });
      this.port.postMessage({ id, job, machine, auto, bedXUm });
    });
  }

  get pending(): number {
    return this.#pending.size;
  }

  /** Ends the worker; what was still asked is refused. */
  close(): void {
    this.port.terminate();
    for (const p of this.#pending.values()) {
      clearTimeout(p.timer);
      p.reject(new Error('planning stopped'));
    }
    this.#pending.clear();
  }

  #settle(reply: PlanReply): void {
    const p = this.#pending.get(reply.id);
    if (!p) return; // timed out already
    this.#pending.delete(reply.id);
    clearTimeout(p.timer);
    if ('error' in reply) p.reject(new Error(reply.error));
    else p.resolve(reply.planned);
  }
}
