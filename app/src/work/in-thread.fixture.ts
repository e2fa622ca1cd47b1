// Test-only: the work worker's answers in the same thread, behind a port like the worker's, for
// code under test that asks the worker (vi.mock the client's spawnWorker with this).
import { answer, BoardUnreadable } from './answer';
import type { WorkPort } from './work-client';
import type { WorkReply } from './work-types';

export function inThreadPort(): WorkPort {
  const port: WorkPort = {
    onmessage: null,
    terminate() {},
    postMessage({ id, request }) {
      const reply = (m: WorkReply) => queueMicrotask(() => port.onmessage?.({ data: m } as MessageEvent<WorkReply>));
      answer(request, (progress) => reply({ id, progress })).then(
        ({ result }) => reply({ id, result }),
        (e: Error) => reply({ id, error: e.message, ...(e instanceof BoardUnreadable ? { problems: e.problems } : {}) }),
      );
    },
  };
  return port;
}
