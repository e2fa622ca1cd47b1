import { describe, expect, it } from 'vitest';
import { servedByEsp, STATUS_RETRY_MS } from './esp-status';

const json = (status: number, body: unknown) => new Response(JSON.stringify(body), { status, headers: { 'content-type': 'application/json' } });
const SNAPSHOT = { mega: { connected: true }, job: null };

/** Answers each GET /status with the next reply, and keeps the waits it was asked for. */
function hub(...replies: (Response | Error)[]) {
  const waits: number[] = [];
  let asked = 0;
  const get = async () => {
    const r = replies[Math.min(asked++, replies.length - 1)];
    if (r instanceof Error) throw r;
    return r;
  };
  return { get, wait: async (ms: number) => void waits.push(ms), waits, asked: () => asked };
}

describe('servedByEsp', () => {
  it('is the hub when GET /status answers its snapshot', async () => {
    const h = hub(json(200, SNAPSHOT));
    expect(await servedByEsp('http://192.168.4.1', h.get, h.wait)).toBe(true);
    expect(h.waits).toEqual([]);
  });

  it('asks again after a 503 overloaded, with a back-off', async () => {
    const h = hub(json(503, { error: { code: 'overloaded', message: 'try again' } }), json(503, { error: { code: 'overloaded', message: 'try again' } }), json(200, SNAPSHOT));
    expect(await servedByEsp('http://192.168.4.1', h.get, h.wait)).toBe(true);
    expect(h.waits).toEqual([250, 500]);
  });

  it('asks again when no answer came', async () => {
    const h = hub(new TypeError('Failed to fetch'), json(200, SNAPSHOT));
    expect(await servedByEsp('http://192.168.4.1', h.get, h.wait)).toBe(true);
    expect(h.waits).toEqual([250]);
  });

  it('gives up after the back-off, never waiting for ever', async () => {
    const h = hub(json(503, { error: { code: 'overloaded', message: 'try again' } }));
    expect(await servedByEsp('http://192.168.4.1', h.get, h.wait)).toBe(false);
    expect(h.waits).toEqual(STATUS_RETRY_MS);
    expect(h.asked()).toBe(STATUS_RETRY_MS.length + 1);
  });

  it('is not the hub on a 404 or a page that is not its snapshot, at once', async () => {
    for (const r of [new Response('not found', { status: 404 }), new Response('<!doctype html>', { status: 200, headers: { 'content-type': 'text/html' } }), json(200, { other: 1 })]) {
      const h = hub(r);
      expect(await servedByEsp('http://x', h.get, h.wait)).toBe(false);
      expect(h.waits).toEqual([]);
    }
  });
});
