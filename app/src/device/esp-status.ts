// Whether the page was served by the printer's hub (protocol/esp.md): its GET /status, asked with a back-off.

/** How long to wait before asking GET /status again, after a 503 or no answer: back-off, 3.75 s in all. */
export const STATUS_RETRY_MS = [250, 500, 1000, 2000];

/**
 * The ESP serves the app and answers GET /status with its snapshot; anything else means no ESP here.
 * A 503 (`overloaded`: more requests already wait for its main loop, esp.md) or a request that got no
 * answer is asked again after a back-off: one busy moment of the hub must not decide.
 */
export async function servedByEsp(
  origin = location.origin,
  get: (url: string, init: RequestInit) => Promise<Response> = (url, init) => fetch(url, init),
  wait = (ms: number) => new Promise<void>((r) => setTimeout(r, ms)),
): Promise<boolean> {
  for (let attempt = 0; ; attempt++) {
    try {
      const r = await get(`${origin}/status`, { headers: { accept: 'application/json' } });
      if (r.status !== 503) {
        if (!r.ok || !(r.headers.get('content-type') ?? '').includes('application/json')) return false;
        const body = await r.json();
        return typeof body === 'object' && body !== null && 'mega' in body;
      }
    } catch {
      // no answer: asked again below
    }
    if (attempt >= STATUS_RETRY_MS.length) return false;
    await wait(STATUS_RETRY_MS[attempt]);
  }
}
