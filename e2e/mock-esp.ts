// Test-only: the ESP of protocol/esp.md as the page sees it, through page.route and page.routeWebSocket.
// Behind it runs the simulated printer, driven by the same windowed dialect client the app uses.
import type { Page, Route, WebSocketRoute } from '@playwright/test';
import { existsSync, readFileSync } from 'node:fs';
import { extname, join, normalize } from 'node:path';
import { DialectClient } from '../app/src/device/dialect-client';
import type { Reply } from '../app/src/protocol/dialect-reply';
import { formatReply } from '../app/src/protocol/reply-format';
import { encodeJob } from '../app/src/protocol/job-encode';
import { validatePrintRequest } from '../app/src/protocol/print-request';
import type { SimOptions } from '../app/src/sim/sim-printer';
import { NodeSim } from './node-sim';

export class MockEsp {
  readonly sim: NodeSim;
  readonly client: DialectClient;
  #sockets = new Set<WebSocketRoute>();
  #job: { id: number; state: string; bytesSent: number; bytesVerified: number; bytesTotal: number } | null = null;
  #jobs = 0;
  #ready: Promise<void>;
  #wifi = { apSsid: 'UVPrinter-5EED01', apPassword: 'abcdefghjkmn', staSsid: '', staPassword: '' };
  #statusTimer: ReturnType<typeof setInterval> | null = null;
  #heartbeat: ReturnType<typeof setInterval>;
  #cancelled = false;
  /** What the hub last heard of the Mega, as the real one keeps it from the Mega's reports. */
  /** The job format the Mega's M115 says it reads (`Cap:JOB_FORMAT`), which the hub writes. */
  #jobFormat: 1 | 2 = 1;
  #heard: { firmware: string; temps: number[]; pos: number[]; job: Extract<Reply, { kind: 'job' }> | null; probe: string | null; limits: number[] } = {
    firmware: '', temps: [], pos: [0, 0, 0], job: null, probe: null, limits: [],
  };

  constructor(options: SimOptions = {}, speed = 1) {
    this.sim = new NodeSim(options, speed);
    const transport = {
      kind: 'serial' as const,
      open: async (onBytes: (b: string) => void) => this.sim.connect(onBytes),
      send: async (bytes: string) => this.sim.receive(bytes),
      close: async () => {},
    };
    // As the ESP: the oks that answer an upload's records are not relayed (esp.md `line`).
    this.client = new DialectClient(transport, (r, line) => {
      this.#hear(r);
      if (!(r.kind === 'ok' && this.#job?.state === 'uploading')) this.#broadcast({ type: 'line', line });
    });
    // As the hub: who the Mega is, its limits, and its reports every second from then on.
    this.#ready = this.client.open(() => {}).then(async () => {
      for (const line of ['M115', 'M503', 'M155 S1', 'M154 S1', 'M27 S1']) (await this.client.command(line)).forEach((r) => this.#hear(r));
    });
    // As the hub: an M105 every 10 s of the printer's time, or the Mega pauses a job as hostless (mega.md §6).
    this.#heartbeat = setInterval(() => void this.#ready.then(() => this.client.command('M105')).catch(() => {}), 10_000 / speed);
  }

  #hear(r: Reply): void {
    const h = this.#heard;
    if (r.kind === 'firmware') (h.firmware = r.name), (this.#jobFormat = 1); // an M115 answer: format 1 unless it says more
    else if (r.kind === 'cap' && r.name === 'JOB_FORMAT') this.#jobFormat = r.value >= 2 ? 2 : 1;
    else if (r.kind === 'temps') h.temps = r.deciC.map((d) => d / 10);
    else if (r.kind === 'position') h.pos = r.um.map((u) => u / 1000);
    else if (r.kind === 'job') h.job = r;
    else if (r.kind === 'probe') h.probe = r.state;
    else if (r.kind === 'other') {
      const m = /^M850 thermal\.limit\.(\d) ([\d.]+)$/.exec(r.text);
      if (m) h.limits[Number(m[1])] = Number(m[2]);
    }
  }

  /** A job running or paused, as the Mega's last JOB: report says. */
  get #running(): boolean {
    const state = this.#heard.job?.state;
    return state === 'running' || state === 'paused';
  }

  async install(page: Page): Promise<void> {
    // The hub serves the app from its flash: the ESP's own build (npm run build:esp), which is the
    // one that asks GET /status. Registered first, so the API routes below take precedence.
    await page.route('**/*', serveEspApp);
    await page.route('**/status', (route) =>
      route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify(this.#status()) }),
    );
    await page.route('**/wifi', (route) => this.#wifiRoute(route));
    await page.route('**/print', async (route) => {
      const req = route.request();
      if (req.method() === 'DELETE') {
        const running = this.#running;
        const uploading = this.#job?.state === 'uploading';
        if (!uploading && !running) return route.fulfill({ status: 409, contentType: 'application/json', body: JSON.stringify({ error: { code: 'busy', message: 'nothing to cancel' } }) });
        this.#cancelled = uploading;
        await this.client.command('M524').catch(() => {}); // ends an upload (nothing kept) or the running job
        return route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify({ job: { state: 'aborted' } }) });
      }
      if (req.method() !== 'POST') return route.fulfill({ status: 405, contentType: 'application/json', body: JSON.stringify({ error: { code: 'method_not_allowed', message: req.method() } }) });
      if (!(req.headers()['content-type'] ?? '').startsWith('application/json')) {
        return route.fulfill({ status: 415, contentType: 'application/json', body: JSON.stringify({ error: { code: 'unsupported_media_type', message: 'send application/json' } }) });
      }
      if (this.#job && (this.#job.state === 'uploading' || this.#job.state === 'started')) {
        if (this.#job.state === 'uploading' || this.#running) {
          return route.fulfill({ status: 409, contentType: 'application/json', body: JSON.stringify({ error: { code: 'busy', message: 'a job is uploading or running' } }) });
        }
      }
      const body = req.postData() ?? '';
      const v = validatePrintRequest(body);
      if (v.status !== 202) {
        return route.fulfill({ status: v.status, contentType: 'application/json', body: JSON.stringify({ error: { code: v.error, message: v.message, ...(v.path !== undefined ? { path: v.path } : {}) } }) });
      }
      const id = ++this.#jobs;
      const text = encodeJob(v.job, this.#jobFormat); // as the hub: the newest format its Mega reads
      this.#job = { id, state: 'uploading', bytesSent: 0, bytesVerified: 0, bytesTotal: text.length };
      this.#cancelled = false;
      void this.#upload(id, text, v.paced);
      return route.fulfill({ status: 202, contentType: 'application/json', body: JSON.stringify({ job: { id, state: 'uploading', cells: v.job.grid.cols * v.job.grid.rows } }) });
    });
    await page.routeWebSocket('**/ws', (ws) => {
      if (this.#sockets.size >= 4) return ws.close({ code: 1013, reason: 'too many clients' });
      this.#sockets.add(ws);
      ws.onClose(() => this.#sockets.delete(ws));
      ws.send(JSON.stringify({ type: 'hello', protocol: 1, firmware: 'UVExposure ESP 0.1.0 (mock)' }));
      ws.send(JSON.stringify({ type: 'status', status: this.#status() }));
      this.#statusTimer ??= setInterval(() => this.#broadcast({ type: 'status', status: this.#status() }), 1000);
      ws.onMessage(async (raw) => {
        const error = (code: string, message: string, id?: number) =>
          ws.send(JSON.stringify({ type: 'error', code, message, ...(id !== undefined ? { id } : {}) }));
        const text = String(raw);
        if (text.length > 256) return error('too_large', 'a message is at most 256 bytes, in one frame');
        let m: { type?: unknown; line?: unknown; id?: unknown };
        try {
          m = JSON.parse(text);
        } catch {
          return error('bad_json', 'not JSON');
        }
        if (typeof m !== 'object' || m === null || Array.isArray(m) || typeof m.type !== 'string') return error('bad_message', 'expected an object with a type');
        // As the ESP: an integer that a signed 64-bit integer holds (-2^63 <= id < 2^63).
        const int64 = (v: unknown) => Number.isInteger(v) && (v as number) >= -(2 ** 63) && (v as number) < 2 ** 63;
        if (m.id !== undefined && !int64(m.id)) return error('bad_message', 'id must be an integer');
        const id = m.id as number | undefined;
        if (m.type === 'ping') return ws.send(JSON.stringify({ type: 'pong' }));
        if (m.type !== 'send') return error('unknown_type', 'type must be send or ping', id);
        if (typeof m.line !== 'string') return error('bad_message', 'send needs a line', id);
        if (m.line.length < 1 || m.line.length > 72) return error('line_too_long', 'a line is 1-72 bytes', id);
        if (!/^[\x20-\x7e]+$/.test(m.line)) return error('bad_line', 'a line is printable ASCII, one line', id);
        await this.#ready;
        this.#broadcast({ type: 'sent', line: m.line, from: 'ws' });
        try {
          const replies = await this.client.command(m.line);
          if (id !== undefined) ws.send(JSON.stringify({ type: 'reply', id, lines: [...replies.map((r) => formatReply(r)), 'ok'] }));
        } catch (e) {
          if (id !== undefined) ws.send(JSON.stringify({ type: 'reply', id, lines: [`Error:${(e as Error).message}`, 'ok'] }));
        }
      });
    });
  }

  /** GET and POST /wifi: the settings, never their passwords. */
  #wifiRoute(route: Route): Promise<void> {
    const req = route.request();
    const json = (status: number, body: object) => route.fulfill({ status, contentType: 'application/json', body: JSON.stringify(body) });
    const bad = (message: string, path: string) => json(400, { error: { code: 'bad_job', message, path } });
    if (req.method() === 'GET') return json(200, { apSsid: this.#wifi.apSsid, staSsid: this.#wifi.staSsid });
    if (req.method() !== 'POST') return json(405, { error: { code: 'method_not_allowed', message: 'wrong method for this path' } });
    if (!/^application\/json\s*(;|$)/i.test(req.headers()['content-type'] ?? '')) {
      return json(415, { error: { code: 'unsupported_media_type', message: 'send the body as application/json' } });
    }
    let body: Record<string, unknown>;
    try {
      body = JSON.parse(req.postData() ?? '');
    } catch {
      return json(400, { error: { code: 'bad_json', message: 'send {apPassword?, staSsid?, staPassword?} as JSON, under 1 KB' } });
    }
    const passphrase = (v: unknown) => typeof v === 'string' && /^[\x20-\x7e]{8,63}$/.test(v);
    const unknown = Object.keys(body).find((k) => !['apPassword', 'staSsid', 'staPassword'].includes(k));
    if (unknown) return bad('unknown field', `/${unknown}`);
    if ('apPassword' in body && !passphrase(body.apPassword)) return bad('8-63 printable ASCII characters (WPA2)', '/apPassword');
    // Counted in UTF-8 bytes as the ESP counts them; a lone surrogate has no UTF-8 form (it comes
    // back from the round trip as U+FFFD).
    const utf8 = (v: string) => new TextEncoder().encode(v);
    const ssid = (v: unknown) =>
      typeof v === 'string' && new TextDecoder().decode(utf8(v)) === v && utf8(v).length <= 32 && !/[\x00-\x1f\x7f]/.test(v);
    if ('staSsid' in body && !ssid(body.staSsid)) return bad('a network name of 0-32 bytes of UTF-8 text', '/staSsid');
    if ('staPassword' in body && !(body.staPassword === '' || passphrase(body.staPassword))) {
      return bad('empty (an open network) or 8-63 printable ASCII', '/staPassword');
    }
    Object.assign(this.#wifi, body);
    return json(200, { apSsid: this.#wifi.apSsid, staSsid: this.#wifi.staSsid });
  }

  async #upload(id: number, text: string, paced: boolean): Promise<void> {
    const job = this.#job!;
    const tell = () => this.#broadcast({ type: 'upload', id, bytesSent: job.bytesSent, bytesVerified: job.bytesVerified, bytesTotal: job.bytesTotal, state: job.state });
    try {
      await this.#ready;
      const file = `JOB${id}.UVJ`;
      const esp = (line: string) => {
        this.#broadcast({ type: 'sent', line, from: 'esp' });
        return this.client.command(line);
      };
      await esp(`M28 ${file}`);
      await this.client.stream(text.trimEnd().split('\n'), (sent, verified) => {
        job.bytesSent = sent;
        job.bytesVerified = verified;
        tell();
      });
      await esp('M29');
      await esp(`M23 ${file}`);
      await esp(paced ? 'M24 P1' : 'M24'); // as the hub: a paced job starts paced (mega.md "Pacing")
      job.state = 'started';
      tell();
    } catch (e) {
      job.state = 'failed';
      const error = this.#cancelled ? 'cancelled' : (e as Error).message;
      this.#broadcast({ type: 'upload', id, bytesSent: job.bytesSent, bytesVerified: job.bytesVerified, bytesTotal: job.bytesTotal, state: 'failed', error });
    }
  }

  #status() {
    const h = this.#heard;
    const job = h.job;
    const upload = this.#job;
    const stop = /^(\d+)\/(\d+)$/.exec(job?.fields.stop ?? '');
    return {
      mega: 'online',
      firmware: h.firmware,
      position: { x: h.pos[0], y: h.pos[1], z: h.pos[2] },
      temps: h.temps,
      limits: h.limits,
      job:
        (!job || job.state === 'idle') && !upload
          ? null
          : {
              state: job?.state ?? 'idle',
              file: job?.fields.file ?? null,
              stop: stop ? Number(stop[1]) : 0,
              stops: stop ? Number(stop[2]) : 0,
              id: upload?.id ?? null,
              ...(upload ? { upload: upload.state, bytesSent: upload.bytesSent, bytesVerified: upload.bytesVerified, bytesTotal: upload.bytesTotal } : {}),
            },
      probe: h.probe === 'deployed' || h.probe === 'triggered',
      faults: [],
      clients: this.#sockets.size,
    };
  }

  #broadcast(m: object): void {
    const s = JSON.stringify(m);
    for (const ws of this.#sockets) ws.send(s);
  }

  stop(): void {
    if (this.#statusTimer) clearInterval(this.#statusTimer);
    clearInterval(this.#heartbeat);
    this.sim.stop();
  }
}

const ESP_APP = join(import.meta.dirname, '..', 'dist', 'esp-app');
const TYPES: Record<string, string> = {
  '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.svg': 'image/svg+xml',
  '.webmanifest': 'application/manifest+json', '.json': 'application/json',
};

/** A file of the ESP's app build, as the hub serves it; anything else goes on to the next route. */
async function serveEspApp(route: Route): Promise<void> {
  const path = new URL(route.request().url()).pathname;
  const file = join(ESP_APP, normalize(path === '/' ? '/index.html' : path));
  if (!file.startsWith(ESP_APP) || !existsSync(file) || route.request().method() !== 'GET') return route.fallback();
  return route.fulfill({ status: 200, contentType: TYPES[extname(file)] ?? 'application/octet-stream', body: readFileSync(file) });
}
