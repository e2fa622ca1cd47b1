import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { nextTurn, whenIdle } from './later';

describe('nextTurn', () => {
  let frames: (() => void)[] = [];
  beforeEach(() => {
    vi.useFakeTimers();
    frames = [];
    vi.stubGlobal('requestAnimationFrame', (f: () => void) => frames.push(f));
  });
  afterEach(() => {
    vi.useRealTimers();
    vi.unstubAllGlobals();
  });
  const drawFrame = async () => {
    const due = frames.splice(0);
    due.forEach((f) => f());
    await vi.advanceTimersByTimeAsync(0);
  };

  it('gives each part a frame and a task of its own, in the order asked', async () => {
    const order: string[] = [];
    void nextTurn().then(() => order.push('dashboards'));
    void nextTurn().then(() => order.push('console'));
    await vi.advanceTimersByTimeAsync(0);
    expect(order).toEqual([]); // no frame yet
    await drawFrame();
    expect(order).toEqual(['dashboards']); // the console waits for the next frame
    await drawFrame();
    expect(order).toEqual(['dashboards', 'console']);
  });

  it('does not wait past 200 ms for a frame that never comes (a background tab)', async () => {
    let done = false;
    void nextTurn().then(() => (done = true));
    await vi.advanceTimersByTimeAsync(150);
    expect(done).toBe(false);
    await vi.advanceTimersByTimeAsync(100);
    expect(done).toBe(true);
  });
});

describe('whenIdle', () => {
  afterEach(() => {
    vi.useRealTimers();
    vi.unstubAllGlobals();
  });

  it('asks for an idle callback with the latest time, and can be called off', () => {
    const asked: { timeout?: number }[] = [];
    const cancelled: number[] = [];
    vi.stubGlobal('requestIdleCallback', (_f: () => void, o: { timeout?: number }) => (asked.push(o), 7));
    vi.stubGlobal('cancelIdleCallback', (id: number) => cancelled.push(id));
    const off = whenIdle(() => {}, 300);
    off();
    expect(asked).toEqual([{ timeout: 300 }]);
    expect(cancelled).toEqual([7]);
  });

  it('runs the work after at most a second where the browser has no idle callback', async () => {
    vi.useFakeTimers();
    vi.stubGlobal('requestIdleCallback', undefined);
    const work = vi.fn();
    whenIdle(work);
    await vi.advanceTimersByTimeAsync(999);
    expect(work).not.toHaveBeenCalled();
    await vi.advanceTimersByTimeAsync(1);
    expect(work).toHaveBeenCalledOnce();
  });
});
