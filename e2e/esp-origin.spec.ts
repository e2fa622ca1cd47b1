// protocol/esp.md "Who may drive it", against the ESP's core on the host (real HTTP and WebSocket):
// a page on another origin tries every path that drives the printer or changes its settings and
// gets nowhere; the hub's own pages, its AP address and uvprinter.local still work; a slow client
// is cut off at its deadline and holds nothing.
import { expect, test } from '@playwright/test';
import { createServer, request, type Server } from 'node:http';
import { connect } from 'node:net';
import { startEspHost, type EspHost } from './esp-host';

interface Reply {
  status: number;
  body: string;
}

// A request from Node, with exactly the headers given (a browser would add Origin by itself).
function send(base: string, method: string, path: string, headers: Record<string, string>, body?: string): Promise<Reply> {
  return new Promise((resolve, reject) => {
    const r = request(new URL(path, base), { method, headers }, (res) => {
      let text = '';
      res.on('data', (d: Buffer) => (text += d.toString()));
      res.on('end', () => resolve({ status: res.statusCode ?? 0, body: text }));
    });
    r.on('error', reject);
    r.end(body);
  });
}

// A WebSocket handshake by hand: the status line the hub answers it with.
function handshake(base: string, headers: Record<string, string>): Promise<string> {
  const { port } = new URL(base);
  return new Promise((resolve) => {
    const s = connect(Number(port), '127.0.0.1', () => {
      const extra = Object.entries(headers).map(([k, v]) => `${k}: ${v}\r\n`).join('');
      s.write(`GET /ws HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n${extra}\r\n`);
    });
    let got = '';
    s.on('data', (d) => {
      got += d.toString();
      if (got.includes('\r\n\r\n')) {
        s.destroy();
        resolve(got.split('\r\n')[0]);
      }
    });
    s.on('close', () => resolve(got.split('\r\n')[0]));
  });
}

const job = JSON.stringify({
  grid: { cols: 1, rows: 1 },
  pitchUm: { x: 100, y: 100 },
  originUm: { x: 10000, y: 10000 },
  dose: { map: 'linear', fullUs: 100 },
  leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
  strategy: { name: 'raster' },
  gridData: [[255]],
});

let hub: EspHost;
let foreign: Server;
let foreignUrl = '';

test.beforeAll(async () => {
  hub = await startEspHost(20);
  // The other site: a page on another loopback port, as a page on the internet would be.
  foreign = createServer((_, res) => res.writeHead(200, { 'content-type': 'text/html' }).end('<!doctype html><title>another site</title>'));
  await new Promise<void>((resolve) => foreign.listen(0, '127.0.0.1', resolve));
  const address = foreign.address();
  foreignUrl = `http://127.0.0.1:${typeof address === 'object' && address ? address.port : 0}/`;
});

test.afterAll(() => {
  hub.stop();
  foreign.close();
});

test('a page on another origin cannot open /ws, print, cancel or change the Wi-Fi', async ({ page }) => {
  await expect.poll(async () => JSON.parse((await send(hub.url, 'GET', '/status', {})).body).mega, { timeout: 10000 }).toBe('online');
  const before = JSON.parse((await send(hub.url, 'GET', '/wifi', {})).body);
  await page.goto(foreignUrl);
  const tried = await page.evaluate(
    async ([hubUrl, job]) => {
      const socket = await new Promise<string>((resolve) => {
        const ws = new WebSocket(hubUrl.replace(/^http/, 'ws') + '/ws');
        ws.onopen = () => resolve('open');
        ws.onmessage = () => resolve('message');
        ws.onerror = () => resolve('refused');
        setTimeout(() => resolve('timeout'), 5000);
      });
      // What a page may send without a preflight: text/plain POSTs, their answers unreadable to it.
      const simple = async (path: string, body: string) => {
        try {
          await fetch(hubUrl + path, { method: 'POST', mode: 'no-cors', headers: { 'content-type': 'text/plain' }, body });
          return 'sent';
        } catch {
          return 'failed';
        }
      };
      const wifi = await simple('/wifi', JSON.stringify({ staSsid: 'evil', staPassword: 'evil-pass', apPassword: 'evil-pass' }));
      const print = await simple('/print', job);
      // And what needs a preflight, which the hub never grants.
      const preflighted = async (method: string, path: string, body?: string) => {
        try {
          const r = await fetch(hubUrl + path, { method, headers: { 'content-type': 'application/json' }, body });
          return `answered ${r.status}`;
        } catch {
          return 'failed';
        }
      };
      return {
        socket,
        wifi,
        print,
        jsonPrint: await preflighted('POST', '/print', job),
        jsonWifi: await preflighted('POST', '/wifi', JSON.stringify({ staSsid: 'evil' })),
        cancel: await preflighted('DELETE', '/print'),
      };
    },
    [hub.url.replace(/\/$/, ''), job] as const,
  );
  expect(tried.socket).not.toBe('open');
  expect(tried.socket).not.toBe('message');
  expect(tried.jsonPrint).toBe('failed');
  expect(tried.jsonWifi).toBe('failed');
  expect(tried.cancel).toBe('failed');
  // Nothing changed, and no job was taken.
  expect(JSON.parse((await send(hub.url, 'GET', '/wifi', {})).body)).toEqual(before);
  const status = JSON.parse((await send(hub.url, 'GET', '/status', {})).body);
  expect(status.job?.id ?? null).toBeNull();
  expect(status.clients).toBe(0);
});

test('each path answers a foreign Origin 403 foreign_origin and a text body 415, before anything changes', async () => {
  const evil = { origin: 'http://evil.example' };
  const json = { 'content-type': 'application/json' };
  for (const [method, path, headers, body] of [
    ['POST', '/print', { ...evil, ...json }, job],
    ['POST', '/print', { origin: foreignUrl.replace(/\/$/, ''), ...json }, job],
    ['POST', '/wifi', { ...evil, ...json }, '{"staSsid":"evil"}'],
    ['POST', '/wifi', { origin: 'null', ...json }, '{"staSsid":"evil"}'],
    ['DELETE', '/print', evil, undefined],
    ['POST', '/wifi', { ...evil, 'content-type': 'text/plain' }, '{"staSsid":"evil"}'],
  ] as const) {
    const r = await send(hub.url, method, path, headers, body);
    expect(r.status, `${method} ${path} ${JSON.stringify(headers)}`).toBe(403);
    expect(JSON.parse(r.body).error.code).toBe('foreign_origin');
  }
  // A rebound DNS name: the page's origin and Host agree, but the name is not the hub's.
  const rebound = await send(hub.url, 'POST', '/wifi', { host: 'evil.example', origin: 'http://evil.example', ...json }, '{"staSsid":"evil"}');
  expect(rebound.status).not.toBe(200);
  for (const [path, body] of [
    ['/wifi', '{"staSsid":"evil"}'],
    ['/print', job],
  ]) {
    const r = await send(hub.url, 'POST', path, { 'content-type': 'text/plain' }, body);
    expect(r.status, path).toBe(415);
    expect(JSON.parse(r.body).error.code).toBe('unsupported_media_type');
  }
  expect(await handshake(hub.url, evil)).toMatch(/^HTTP\/1\.1 403/);
  expect(await handshake(hub.url, { origin: foreignUrl.replace(/\/$/, '') })).toMatch(/^HTTP\/1\.1 403/);
  expect(JSON.parse((await send(hub.url, 'GET', '/wifi', {})).body).staSsid).toBe('');
});

test("the hub's own origin, its AP address, uvprinter.local and a tool without Origin are taken", async ({ page }) => {
  const json = { 'content-type': 'application/json' };
  const { port } = new URL(hub.url);
  for (const [host, origin] of [
    [`127.0.0.1:${port}`, `http://127.0.0.1:${port}`],
    ['192.168.4.1', 'http://192.168.4.1'],
    ['uvprinter.local', 'http://uvprinter.local'],
  ]) {
    const r = await send(hub.url, 'POST', '/wifi', { host, origin, ...json }, JSON.stringify({ staSsid: 'workshop' }));
    expect(r.status, origin).toBe(200);
    expect(await handshake(hub.url, { origin: `http://127.0.0.1:${port}` })).toMatch(/^HTTP\/1\.1 101/);
  }
  expect((await send(hub.url, 'POST', '/wifi', json, JSON.stringify({ staSsid: '' }))).status).toBe(200); // curl, OctoPrint
  expect((await send(hub.url, 'DELETE', '/print', {})).status).toBe(409); // judged: nothing to cancel
  // And the app itself, from the hub's flash, in the browser.
  await page.goto(hub.url);
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const fromApp = await page.evaluate(async () => (await fetch('/wifi', { method: 'POST', headers: { 'content-type': 'application/json' }, body: '{"staSsid":""}' })).status);
  expect(fromApp).toBe(200);
});

test('a slow client is cut off at its deadline and holds neither the spool nor a socket', async () => {
  const slow = await startEspHost(20, ['--request-deadline-ms', '1500']);
  try {
    await expect.poll(async () => JSON.parse((await send(slow.url, 'GET', '/status', {})).body).mega, { timeout: 10000 }).toBe('online');
    const { port } = new URL(slow.url);
    // A body that comes a byte at a time, each under the ESP library's 3 s idle time-out.
    const s = connect(Number(port), '127.0.0.1');
    let closed = false;
    s.on('close', () => (closed = true));
    s.on('error', () => {});
    await new Promise<void>((resolve) => s.once('connect', () => resolve()));
    s.write(`POST /print HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nContent-Type: application/json\r\nContent-Length: ${job.length}\r\n\r\n{`);
    const drip = setInterval(() => !closed && s.write(' '), 300);
    expect((await send(slow.url, 'POST', '/print', { 'content-type': 'application/json' }, '{"grid":')).status).toBe(409); // it holds the spool
    await expect.poll(() => closed, { timeout: 5000 }).toBe(true);
    clearInterval(drip);
    expect((await send(slow.url, 'POST', '/print', { 'content-type': 'application/json' }, '{"grid":')).status).toBe(400); // judged afresh
    // A header line that never ends is cut off too, at its size.
    const long = connect(Number(port), '127.0.0.1');
    let longClosed = false;
    long.on('close', () => (longClosed = true));
    long.on('error', () => {});
    await new Promise<void>((resolve) => long.once('connect', () => resolve()));
    long.write(`GET /status HTTP/1.1\r\nX-Filler: ${'a'.repeat(8192)}`);
    await expect.poll(() => longClosed, { timeout: 3000 }).toBe(true);
    // A DELETE frees the spool of a stalled body at once, without waiting for its deadline.
    const stalled = connect(Number(port), '127.0.0.1');
    stalled.on('error', () => {});
    await new Promise<void>((resolve) => stalled.once('connect', () => resolve()));
    stalled.write(`POST /print HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nContent-Type: application/json\r\nContent-Length: ${job.length}\r\n\r\n{`);
    await new Promise((r) => setTimeout(r, 200));
    expect((await send(slow.url, 'POST', '/print', { 'content-type': 'application/json' }, '{"grid":')).status).toBe(409);
    expect((await send(slow.url, 'DELETE', '/print', {})).status).toBe(200);
    expect((await send(slow.url, 'POST', '/print', { 'content-type': 'application/json' }, '{"grid":')).status).toBe(400);
    stalled.destroy();
  } finally {
    slow.stop();
  }
});
