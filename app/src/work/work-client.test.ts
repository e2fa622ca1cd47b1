import { afterEach, describe, expect, it, vi } from 'vitest';
import { DEFAULT_CONFIG, motionOf } from '../studio/machine-config';
import { testPattern } from '../device/test-pattern';
import type { Planned } from '../preview/plan-work';
import type { PreviewGrid } from '../preview/exposure-preview';
import { Cancelled, WorkClient, type WorkPort } from './work-client';
import { keptGrid, planForPreview } from './preview-work';
import type { WorkReply, WorkRequest } from './work-types';

/** A worker in the same thread: answers plans and grids when told, in any order, and says how far it got. */
class FakeWorker implements WorkPort {
  onmessage: ((e: MessageEvent<WorkReply>) => void) | null = null;
  asked: { id: number; request: WorkRequest }[] = [];
  terminated = false;
  postMessage(m: { id: number; request: WorkRequest }) {
    this.asked.push(m);
  }
  terminate() {
    this.terminated = true;
  }
  send(reply: WorkReply) {
    this.onmessage?.({ data: reply } as MessageEvent<WorkReply>);
  }
  answer(i: number) {
    const { id, request } = this.asked[i];
    this.send({ id, progress: { stage: 'planning' } });
    if (request.kind === 'plan') this.send({ id, result: planForPreview(request).result });
    else if (request.kind === 'preview-grid') this.send({ id, result: keptGrid(request.upTo, request.maxSide).result });
    else this.send({ id, error: `no ${request.kind} here` });
  }
}

afterEach(() => vi.useRealTimers());

describe('heavy work off the page\'s thread', () => {
  const machine = motionOf(DEFAULT_CONFIG);
  it('settles each request by its id, whatever order the replies come in, with progress on the way', async () => {
    const workers: FakeWorker[] = [];
    const client = new WorkClient(() => (workers.push(new FakeWorker()), workers.at(-1)!));
    const stages: string[] = [];
    const slow = client.call<Planned>({ kind: 'plan', job: testPattern(4000), machine }, { onProgress: (p) => stages.push(p.stage) });
    const fast = client.call<Planned>({ kind: 'plan', job: testPattern(1_000_000), machine });
    expect(workers).toHaveLength(1); // one worker for both
    const w = workers[0];
    expect(w.asked.map((r) => r.id)).toEqual([1, 2]);
    w.answer(1);
    w.answer(0);
    const [a, b] = await Promise.all([slow, fast]);
    expect(b.plan.estimateUs).toBeGreaterThan(a.plan.estimateUs * 10); // a full dose of 1000 ms against 4 ms
    expect(a.clock.length).toBe(a.plan.count);
    expect(stages).toEqual(['planning']);
    expect(client.pending).toBe(0);
  });
  it('bins the plan it kept, up to a stop', async () => {
    const w = new FakeWorker();
    const client = new WorkClient(() => w);
    const planned = client.call<Planned>({ kind: 'plan', job: testPattern(4000), machine });
    w.answer(0);
    const { plan } = await planned;
    const none = client.call<PreviewGrid>({ kind: 'preview-grid', upTo: 0, maxSide: 512 });
    const all = client.call<PreviewGrid>({ kind: 'preview-grid', upTo: plan.count, maxSide: 512 });
    w.answer(1);
    w.answer(2);
    expect((await none).doseUs.some((us) => us > 0)).toBe(false);
    expect((await all).doseUs.some((us) => us > 0)).toBe(true);
    expect((await all).maxUs).toBe((await none).maxUs); // the scale stays while scrubbing
  });
  it('rejects with the worker\'s error', async () => {
    const w = new FakeWorker();
    const client = new WorkClient(() => w);
    const asked = client.call({ kind: 'read-picture', src: 'data:,' });
    w.answer(0);
    await expect(asked).rejects.toThrow('no read-picture here');
  });
  it('gives up on a request the worker does not answer in time, and ignores its late reply', async () => {
    vi.useFakeTimers();
    const w = new FakeWorker();
    const client = new WorkClient(() => w, 1000);
    const asked = client.call({ kind: 'plan', job: testPattern(4000), machine });
    vi.advanceTimersByTime(1001);
    await expect(asked).rejects.toThrow('it took over 1 s');
    w.answer(0);
    expect(client.pending).toBe(0);
  });
  it('cancels: the worker ends, what was asked is refused as cancelled, and the next request starts a fresh worker', async () => {
    const workers: FakeWorker[] = [];
    const client = new WorkClient(() => (workers.push(new FakeWorker()), workers.at(-1)!));
    const stop = new AbortController();
    const asked = client.call({ kind: 'plan', job: testPattern(4000), machine }, { signal: stop.signal });
    const other = client.call({ kind: 'plan', job: testPattern(4000), machine });
    stop.abort();
    await expect(asked).rejects.toBeInstanceOf(Cancelled);
    await expect(other).rejects.toBeInstanceOf(Cancelled);
    expect(workers[0].terminated).toBe(true);
    const again = client.call<Planned>({ kind: 'plan', job: testPattern(4000), machine });
    expect(workers).toHaveLength(2);
    workers[1].answer(0);
    expect((await again).plan.count).toBeGreaterThan(0);
    await expect(client.call({ kind: 'plan', job: testPattern(4000), machine }, { signal: stop.signal })).rejects.toBeInstanceOf(Cancelled); // already aborted
  });
});
