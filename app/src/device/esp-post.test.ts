import { describe, expect, it } from 'vitest';
import { FLASH_BUSY_TRIES, postJob } from './esp-post';

const json = (status: number, body: unknown, headers: Record<string, string> = {}) =>
  new Response(JSON.stringify(body), { status, headers: { 'content-type': 'application/json', ...headers } });
const busy = () => json(503, { error: { code: 'flash_busy', message: 'the ESP is using its flash; try again' } }, { 'retry-after': '1' });
const accepted = () => json(202, { job: { id: 7, state: 'uploading', cells: 32 } });

/** Answers each POST with the next reply, and keeps the bodies and waits it was given. */
function hub(...replies: (() => Response)[]) {
  const bodies: string[] = [];
  const waits: number[] = [];
  const post = async (_url: string, init: RequestInit) => {
    bodies.push(String(init.body));
    return replies[Math.min(bodies.length - 1, replies.length - 1)]();
  };
  return { post, wait: async (ms: number) => void waits.push(ms), bodies, waits };
}

describe('postJob', () => {
  it('posts the job again after Retry-After while the hub answers 503 flash_busy', async () => {
    const h = hub(busy, busy, accepted);
    const r = await postJob('http://192.168.4.1/print', '{"job":1}', h.post, h.wait);
    expect(r.status).toBe(202);
    expect(h.bodies).toEqual(['{"job":1}', '{"job":1}', '{"job":1}']);
    expect(h.waits).toEqual([1000, 1000]);
  });

  it('gives up after FLASH_BUSY_TRIES posts, with the hub’s last answer', async () => {
    const h = hub(busy);
    const r = await postJob('http://192.168.4.1/print', '{}', h.post, h.wait);
    expect(r.status).toBe(503);
    expect((await r.json()).error.code).toBe('flash_busy');
    expect(h.bodies).toHaveLength(FLASH_BUSY_TRIES);
  });

  it('leaves every other answer to the caller, a 503 of another kind too', async () => {
    for (const reply of [
      () => json(503, { error: { code: 'mega_offline', message: 'the Mega has not been heard for 5 s' } }),
      () => json(409, { error: { code: 'busy', message: 'a job is running' } }),
      () => new Response('not json', { status: 503 }),
    ]) {
      const h = hub(reply, accepted);
      expect((await postJob('http://192.168.4.1/print', '{}', h.post, h.wait)).status).not.toBe(202);
      expect(h.bodies).toHaveLength(1);
    }
  });
});
