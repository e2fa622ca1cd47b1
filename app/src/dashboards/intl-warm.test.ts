// warmIntl: the locale's data loaded in a throwaway worker, or on the page when no worker starts or answers.
import { afterEach, describe, expect, it, vi } from 'vitest';
import { warmIntl } from './intl-warm';

class FakeWorker {
  static made: FakeWorker[] = [];
  onmessage: (() => void) | null = null;
  onerror: (() => void) | null = null;
  terminated = false;
  constructor(readonly url: string) {
    FakeWorker.made.push(this);
  }
  terminate() {
    this.terminated = true;
  }
}

afterEach(() => {
  vi.unstubAllGlobals();
  vi.useRealTimers();
  FakeWorker.made = [];
});

describe('warmIntl', () => {
  it('waits for the worker, ends it, and asks the page for no idle task', async () => {
    vi.stubGlobal('Worker', FakeWorker);
    const idle = vi.fn(async () => {});
    let warmed = false;
    const warming = warmIntl(idle).then(() => (warmed = true));
    await Promise.resolve();
    expect(warmed).toBe(false);
    const [worker] = FakeWorker.made;
    expect(worker.url).toMatch(/^blob:/);
    worker.onmessage!();
    await warming;
    expect(worker.terminated).toBe(true);
    expect(idle).not.toHaveBeenCalled();
  });

  it('makes the formats on the page, in two idle tasks, when the worker fails', async () => {
    vi.stubGlobal('Worker', FakeWorker);
    vi.stubGlobal('navigator', { language: 'de-DE' });
    const idle = vi.fn(async () => {});
    const warming = warmIntl(idle);
    FakeWorker.made[0].onerror!();
    await warming;
    expect(FakeWorker.made[0].terminated).toBe(true);
    expect(idle).toHaveBeenCalledTimes(2);
  });

  it('makes them on the page when the worker never answers', async () => {
    vi.useFakeTimers();
    vi.stubGlobal('Worker', FakeWorker);
    vi.stubGlobal('navigator', { language: 'en-GB' });
    const idle = vi.fn(async () => {});
    const warming = warmIntl(idle, 2000);
    await vi.advanceTimersByTimeAsync(1999);
    expect(idle).not.toHaveBeenCalled();
    await vi.advanceTimersByTimeAsync(1);
    await warming;
    expect(FakeWorker.made[0].terminated).toBe(true);
    expect(idle).toHaveBeenCalledTimes(2);
  });

  it('makes them on the page where no worker can start', async () => {
    vi.stubGlobal('Worker', class {
      constructor() {
        throw new DOMException('blocked by policy', 'SecurityError');
      }
    });
    vi.stubGlobal('navigator', { language: 'fr-FR' });
    const idle = vi.fn(async () => {});
    await warmIntl(idle);
    expect(idle).toHaveBeenCalledTimes(2);
  });
});
