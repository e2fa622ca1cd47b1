// Asks the work worker (worker.ts) to do what would freeze the page: each request carries an id,
// waits in a Map and is settled by the worker's reply or a time-out; on the way the worker may
// report progress. Cancelling ends the worker (its work is one long synchronous run, which nothing
// else can stop) and refuses whatever was still asked; the next request starts a fresh one.

import type { Progress, WorkReply, WorkRequest } from './work-types';

/** What the client needs of a Worker (a test hands it a fake one). */
export interface WorkPort {
  postMessage(m: { id: number; request: WorkRequest }, transfer?: Transferable[]): void;
  onmessage: ((e: MessageEvent<WorkReply>) => void) | null;
  terminate(): void;
}

/** The work was cancelled by the user, or its worker ended: not an error to show. */
export class Cancelled extends Error {
  constructor(what = 'cancelled') {
    super(what);
    this.name = 'Cancelled';
  }
}

export interface CallOptions {
  onProgress?: (p: Progress) => void;
  /** Aborting it cancels this request, and with it everything else the worker was doing. */
  signal?: AbortSignal;
  /** Buffers the request holds that move to the worker instead of being copied (job-transfer.ts): unusable here afterwards. */
  transfer?: Transferable[];
}

type Pending = { resolve: (r: unknown) => void; reject: (e: Error) => void; timer: ReturnType<typeof setTimeout>; onProgress?: (p: Progress) => void };

export class WorkClient {
  #next = 1;
  #port: WorkPort | null = null;
  readonly #pending = new Map<number, Pending>();

  constructor(private readonly spawn: () => WorkPort, private readonly timeoutMs = 120_000) {}

  call<R>(request: WorkRequest, opts: CallOptions = {}): Promise<R> {
    if (opts.signal?.aborted) return Promise.reject(new Cancelled());
    const id = this.#next++;
    const port = this.#open();
    return new Promise<R>((resolve, reject) => {
      const timer = setTimeout(() => {
        this.#pending.delete(id);
        reject(new Error(`it took over ${this.timeoutMs / 1000} s`));
      }, this.timeoutMs);
      this.#pending.set(id, { resolve: resolve as (r: unknown) => void, reject, timer, onProgress: opts.onProgress });
      opts.signal?.addEventListener('abort', () => this.#pending.has(id) && this.cancel(), { once: true });
      port.postMessage({ id, request }, opts.transfer ?? []);
    });
  }

  get pending(): number {
    return this.#pending.size;
  }

  /** Ends the worker; what was still asked is refused as cancelled. */
  cancel(why = 'cancelled'): void {
    this.#port?.terminate();
    this.#port = null;
    for (const p of this.#pending.values()) {
      clearTimeout(p.timer);
      p.reject(new Cancelled(why));
    }
    this.#pending.clear();
  }

  #open(): WorkPort {
    if (!this.#port) {
      this.#port = this.spawn();
      this.#port.onmessage = (e) => this.#settle(e.data);
    }
    return this.#port;
  }

  #settle(reply: WorkReply): void {
    const p = this.#pending.get(reply.id);
    if (!p) return; // timed out or cancelled already
    if ('progress' in reply) return void p.onProgress?.(reply.progress);
    this.#pending.delete(reply.id);
    clearTimeout(p.timer);
    if ('error' in reply) p.reject(Object.assign(new Error(reply.error), reply.problems ? { problems: reply.problems } : {}));
    else p.resolve(reply.result);
  }
}

/** The app's work worker, one instance per client (worker.ts; one file in the build). */
export const spawnWorker = (): WorkPort => new Worker(new URL('./worker.ts', import.meta.url), { type: 'module' }) as unknown as WorkPort;
