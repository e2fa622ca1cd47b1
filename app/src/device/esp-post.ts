// POST /print to the printer's hub (protocol/esp.md), asked again while the hub's flash is busy.

/** How many times a job is posted in all while the hub answers 503 flash_busy. */
export const FLASH_BUSY_TRIES = 4;

/**
 * Posts the job. A `503 flash_busy` (an ESP8266 was inside a flash operation, nothing of the body
 * was kept) is posted again after its `Retry-After` (1 s if it names none), up to FLASH_BUSY_TRIES
 * in all; every other answer, and the last, is the caller's.
 */
export async function postJob(
  url: string,
  body: string,
  post: (url: string, init: RequestInit) => Promise<Response> = (u, init) => fetch(u, init),
  wait = (ms: number) => new Promise<void>((r) => setTimeout(r, ms)),
): Promise<Response> {
  for (let attempt = 1; ; attempt++) {
    const r = await post(url, { method: 'POST', headers: { 'content-type': 'application/json' }, body });
    if (r.status !== 503 || attempt >= FLASH_BUSY_TRIES) return r;
    let code = '';
    try {
      code = (await r.clone().json()).error?.code ?? '';
    } catch {
      /* not the hub's JSON: the caller's */
    }
    if (code !== 'flash_busy') return r;
    const seconds = Number(r.headers.get('retry-after'));
    await wait(Number.isFinite(seconds) && seconds > 0 && seconds <= 10 ? seconds * 1000 : 1000);
  }
}
