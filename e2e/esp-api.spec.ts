// protocol/esp.md from a page, against the ESP's own core on the host (real HTTP and WebSocket), the
// hub every end-to-end test of the Wi-Fi link runs against (transports.ts).
import { expect, test, type Page } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { connect } from 'node:net';
import { join } from 'node:path';
import { startEspHost } from './esp-host';

const vectors = JSON.parse(readFileSync(join(import.meta.dirname, '..', 'protocol', 'vectors', 'esp.json'), 'utf8'));

async function open(page: Page): Promise<() => void> {
  const host = await startEspHost(20);
  await page.goto(host.url);
  return () => host.stop();
}

function call(page: Page, method: string, path: string, body?: string, contentType = 'application/json') {
  return page.evaluate(
    async ([method, path, body, contentType]) => {
      const r = await fetch(path, { method, headers: body === undefined ? {} : { 'content-type': contentType }, body });
      return { status: r.status, json: await r.json() };
    },
    [method, path, body, contentType] as const,
  );
}

// Opens /ws in the page, sends `frames` one at a time, and collects what comes back.
function socket(page: Page, frames: string[], until: string) {
  return page.evaluate(
    async ([frames, until]) => {
      const ws = new WebSocket(location.origin.replace(/^http/, 'ws') + '/ws');
      const got: Record<string, unknown>[] = [];
      await new Promise<void>((resolve, reject) => {
        ws.onerror = () => reject(new Error('no socket'));
        ws.onopen = () => frames.forEach((f) => ws.send(f));
        ws.onmessage = (e) => {
          const m = JSON.parse(String(e.data));
          got.push(m);
          if (JSON.stringify(m).includes(until)) resolve();
        };
        setTimeout(resolve, 8000);
      });
      ws.close();
      return got;
    },
    [frames, until] as const,
  );
}

test.describe('esp API (firmware)', () => {
  test('POST /print answers every vector with its status and field, and DELETE with nothing to cancel is 409', async ({ page }) => {
    const close = await open(page);
    // GET /status first: the hub must have heard the Mega.
    await expect.poll(async () => (await call(page, 'GET', '/status')).json.mega).toBe('online');
    for (const c of vectors.requests) {
      if (c.status === 202) continue; // accepted jobs start uploads: the flows cover them
      const r = await call(page, 'POST', '/print', c.body);
      expect(r.status, c.name).toBe(c.status);
      expect(r.json.error.code, c.name).toBe(c.error);
      if (c.path !== undefined) expect(r.json.error.path, c.name).toBe(c.path);
    }
    expect((await call(page, 'POST', '/print', '{}', 'text/plain')).status).toBe(415);
    expect((await call(page, 'DELETE', '/print')).status).toBe(409);
    const s = (await call(page, 'GET', '/status')).json;
    for (const key of ['mega', 'firmware', 'position', 'temps', 'limits', 'job', 'probe', 'faults', 'clients']) expect(s, key).toHaveProperty(key);
    expect(s.temps).toHaveLength(6);
    close();
  });

  test('GET and POST /wifi keep the password to themselves and refuse a weak one', async ({ page }) => {
    const close = await open(page);
    const got = await call(page, 'GET', '/wifi');
    expect(got.status).toBe(200);
    expect(got.json.apSsid).toMatch(/^UVPrinter-[0-9A-F]{6}$/);
    expect(got.json).not.toHaveProperty('apPassword');
    const weak = await call(page, 'POST', '/wifi', JSON.stringify({ apPassword: 'short' }));
    expect(weak.status).toBe(400);
    expect(weak.json.error.path).toBe('/apPassword');
    // A text body, which a foreign page may send without a preflight, changes nothing.
    expect((await call(page, 'POST', '/wifi', JSON.stringify({ staSsid: 'x' }), 'text/plain')).status).toBe(415);
    const unknown = await call(page, 'POST', '/wifi', JSON.stringify({ colour: 'red' }));
    expect(unknown.json.error.path).toBe('/colour');
    const ok = await call(page, 'POST', '/wifi', JSON.stringify({ apPassword: 'a good long one', staSsid: 'workshop', staPassword: 'hunter22' }));
    expect(ok.status).toBe(200);
    expect(ok.json).toEqual({ apSsid: got.json.apSsid, staSsid: 'workshop' });
    // A name is UTF-8 text, counted in bytes: 16 × "é" is 32 bytes and comes back as it went in.
    const accented = await call(page, 'POST', '/wifi', JSON.stringify({ staSsid: 'é'.repeat(16) }));
    expect(accented.json).toEqual({ apSsid: got.json.apSsid, staSsid: 'é'.repeat(16) });
    for (const staSsid of ['é'.repeat(17), 'tab\there']) {
      const refused = await call(page, 'POST', '/wifi', JSON.stringify({ staSsid }));
      expect(refused.status).toBe(400);
      expect(refused.json.error.path).toBe('/staSsid');
    }
    close();
  });

  test('the WebSocket greets, answers by id, refuses bad frames and stays open', async ({ page }) => {
    const close = await open(page);
    await expect.poll(async () => (await call(page, 'GET', '/status')).json.mega).toBe('online');
    const got = await socket(
      page,
      [
        '{"type":"ping"}',
        'not json',
        '{"type":"shout","id":1}',
        JSON.stringify({ type: 'send', line: 'M'.repeat(73), id: 2 }),
        JSON.stringify({ type: 'send', line: 'M105\nM112', id: 3 }),
        JSON.stringify({ type: 'send', line: 'M115', id: 4 }),
      ],
      '"id":4',
    );
    const seen = JSON.stringify(got); // what came, should an expectation fail
    expect(got[0], seen).toMatchObject({ type: 'hello', protocol: 1 });
    expect(got[1], seen).toMatchObject({ type: 'status' });
    const errors = got.filter((m) => m.type === 'error');
    expect(errors.map((e) => e.code), seen).toEqual(['bad_json', 'unknown_type', 'line_too_long', 'bad_line']);
    expect(errors.map((e) => e.id)).toEqual([undefined, 1, 2, 3]);
    expect(got.some((m) => m.type === 'pong')).toBe(true);
    const reply = got.find((m) => m.type === 'reply' && m.id === 4) as { lines: string[] } | undefined;
    expect(reply, seen).toBeDefined();
    expect(reply!.lines.some((l) => l.startsWith('FIRMWARE_NAME:UVExposure'))).toBe(true);
    expect(reply!.lines.at(-1)).toMatch(/^ok/);
    expect(got.some((m) => m.type === 'sent' && m.line === 'M115' && m.from === 'ws')).toBe(true);
    close();
  });
});

test('esp API (firmware): a POST /print cut off mid-body frees the Mega for the next job', async ({ page }) => {
  const host = await startEspHost(20);
  await page.goto(host.url);
  await expect.poll(async () => (await call(page, 'GET', '/status')).json.mega).toBe('online');
  const { port } = new URL(host.url);
  await new Promise<void>((resolve) => {
    const s = connect(Number(port), '127.0.0.1', () => {
      s.write('POST /print HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: 5000\r\n\r\n{"grid":');
      setTimeout(() => {
        s.destroy(); // the browser tab closed, the Wi-Fi dropped
        resolve();
      }, 300);
    });
  });
  await expect.poll(async () => (await call(page, 'POST', '/print', '{"grid":')).status, { timeout: 5000 }).toBe(400); // not 409: nothing holds the Mega
  host.stop();
});

test('esp API (firmware): a DELETE while a POST /print body arrives cancels that POST, 409, and frees the Mega', async ({ page }) => {
  const host = await startEspHost(20);
  await page.goto(host.url);
  await expect.poll(async () => (await call(page, 'GET', '/status')).json.mega).toBe('online');
  const { port } = new URL(host.url);
  const body = '{"grid":' + ' '.repeat(4992);
  const s = connect(Number(port), '127.0.0.1');
  let reply = '';
  s.on('data', (d) => (reply += d.toString()));
  await new Promise<void>((resolve) => s.once('connect', () => resolve()));
  s.write(`POST /print HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\nContent-Length: ${body.length}\r\n\r\n${body.slice(0, 100)}`);
  await new Promise((resolve) => setTimeout(resolve, 300));
  const cancel = await call(page, 'DELETE', '/print'); // the body is still arriving
  expect(cancel.status).toBe(200);
  expect(cancel.json).toEqual({ job: { state: 'aborted' } });
  s.write(body.slice(100));
  await expect.poll(() => reply, { timeout: 5000 }).toContain('"cancelled"');
  expect(reply).toMatch(/^HTTP\/1\.1 409/);
  expect(reply).toContain('cancelled by DELETE /print');
  s.destroy();
  expect((await call(page, 'DELETE', '/print')).status).toBe(409); // nothing left to cancel
  await expect.poll(async () => (await call(page, 'POST', '/print', '{"grid":')).status, { timeout: 5000 }).toBe(400); // judged afresh, not 409
  host.stop();
});

test('the app from the ESP\'s flash connects over Wi-Fi and has no simulated printer to offer, nor a Firmware tab', async ({ page }) => {
  const host = await startEspHost(20);
  await page.goto(host.url);
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('device-kind')).toHaveValue('esp');
  await expect(page.getByTestId('device-kind').locator('option')).toHaveText(['USB (Web Serial)', 'Wi-Fi (printer hub)']);
  await expect(page.getByTestId('tab-settings')).toBeVisible();
  await expect(page.getByTestId('tab-firmware')).toHaveCount(0); // flashing is the full app's (app/src/firmware/firmware-view.ts)
  host.stop();
});
