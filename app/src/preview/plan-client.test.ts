import { afterEach, describe, expect, it, vi } from 'vitest';
import { DEFAULT_CONFIG, motionOf } from '../studio/machine-config';
import { testPattern } from '../device/test-pattern';
import { PlanClient, type PlanPort, type PlanReply, type PlanRequest } from './plan-client';
import { planReply } from './plan-work';

/** A worker in the same thread: replies when told, in any order. */
class FakeWorker implements PlanPort {
  onmessage: ((e: MessageEvent<PlanReply>) => void) | null = null;
  asked: PlanRequest[] = [];
  terminated = false;
  postMessage(m: PlanRequest) {
    this.asked.push(m);
  }
  terminate() {
    this.terminated = true;
  }
  answer(i: number) {
    this.onmessage?.({ data: planReply(this.asked[i]) } as MessageEvent<PlanReply>);
  }
}

afterEach(() => vi.useRealTimers());

describe('planning off the page\'s thread', () => {
  const machine = motionOf(DEFAULT_CONFIG);
  it('settles each request by its id, whatever order the replies come in', async () => {
    const w = new FakeWorker();
    const client = new PlanClient(w);
    const slow = client.plan(testPattern(4000), machine);
    const fast = client.plan(testPattern(1_000_000), machine);
    expect(w.asked.map((r) => r.id)).toEqual([1, 2]);
    w.answer(1);
    w.answer(0);
    const [a, b] = await Promise.all([slow, fast]);
    expect(b.plan.estimateUs).toBeGreaterThan(a.plan.estimateUs * 10); // a full dose of 1000 ms against 4 ms
    expect(a.clock.length).toBe(a.plan.count);
    expect(client.pending).toBe(0);
  });
  it('gives up on a request the worker does not answer in time, and ignores its late reply', async () => {
    vi.useFakeTimers();
    const w = new FakeWorker();
    const client = new PlanClient(w, 1000);
    const asked = client.plan(testPattern(4000), machine);
    vi.advanceTimersByTime(1001);
    await expect(asked).rejects.toThrow('planning took over 1 s');
    w.answer(0);
    expect(client.pending).toBe(0);
  });
  it('refuses what was still asked when it closes', async () => {
    const w = new FakeWorker();
    const client = new PlanClient(w);
    const asked = client.plan(testPattern(4000), machine);
    client.close();
    await expect(asked).rejects.toThrow('planning stopped');
    expect(w.terminated).toBe(true);
  });
});
