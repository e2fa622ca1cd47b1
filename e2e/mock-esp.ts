// Test-only: the ESP of protocol/esp.md as the page sees it, through page.route and page.routeWebSocket.
// Behind it runs the simulated printer, driven by the same windowed dialect client the app uses.
import type { Page, WebSocketRoute } from '@playwright/test';
import { DialectClient } from '../app/src/device/dialect-client';
import { formatReply } from '../app/src/protocol/dialect-reply';
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

  constructor(options: SimOptions = {}, speed = 1) {
    this.sim = new NodeSim(options, speed);
    const transport = {
      kind: 'serial' as const,
      open: async (onBytes: (b: string) => void) => this.sim.connect(onBytes),
      send: async (bytes: string) => this.sim.receive(bytes),
      close: async () => {},
    };
    this.client = new DialectClient(transport, (_r, line) => this.#broadcast({ type: 'line', line }));
    this.#ready = this.client.open(() => {}).then(() => this.client.command('M115').then(() => {}));
  }

  async install(page: Page): Promise<void> {
    await page.route('**/status', (route) =>
      route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify(this.#status()) }),
    );
    await page.route('**/print', async (route) => {
      const req = route.request();
      if (req.method() === 'DELETE') {
        if (!this.#job) return route.fulfill({ status: 409, contentType: 'application/json', body: JSON.stringify({ error: { code: 'busy', message: 'nothing to cancel' } }) });
        await this.client.command('M524');
        this.#job.state = 'aborted';
        return route.fulfill({ status: 200, contentType: 'application/json', body: JSON.stringify({ job: { state: 'aborted' } }) });
      }
      if (req.method() !== 'POST') return route.fulfill({ status: 405, contentType: 'application/json', body: JSON.stringify({ error: { code: 'method_not_allowed', message: req.method() } }) });
      if (!(req.headers()['content-type'] ?? '').startsWith('application/json')) {
        return route.fulfill({ status: 415, contentType: 'application/json', body: JSON.stringify({ error: { code: 'unsupported_media_type', message: 'send application/json' } }) });
      }
      if (this.#job && (this.#job.state === 'uploading' || this.#job.state === 'started')) {
        const running = this.sim.printer.mega.job.state === 'running' || this.sim.printer.mega.job.state === 'paused';
        if (this.#job.state === 'uploading' || running) {
          return route.fulfill({ status: 409, contentType: 'application/json', body: JSON.stringify({ error: { code: 'busy', message: 'a job is uploading or running' } }) });
        }
      }
      const body = req.postData() ?? '';
      const v = validatePrintRequest(body);
      if (v.status !== 202) {
        return route.fulfill({ status: v.status, contentType: 'application/json', body: JSON.stringify({ error: { code: v.error, message: v.message, ...(v.path !== undefined ? { path: v.path } : {}) } }) });
      }
      const id = ++this.#jobs;
      const text = encodeJob(v.job);
      this.#job = { id, state: 'uploading', bytesSent: 0, bytesVerified: 0, bytesTotal: text.length };
      void this.#upload(id, text);
      return route.fulfill({ status: 202, contentType: 'application/json', body: JSON.stringify({ job: { id, state: 'uploading', cells: v.job.grid.cols * v.job.grid.rows } }) });
    });
    await page.routeWebSocket('**/ws', (ws) => {
      this.#sockets.add(ws);
      ws.onClose(() => this.#sockets.delete(ws));
      ws.send(JSON.stringify({ type: 'hello', protocol: 1, firmware: 'UVExposure ESP 0.1.0 (mock)' }));
      ws.onMessage(async (raw) => {
        let m: { type?: string; line?: string; id?: number };
        try {
          m = JSON.parse(String(raw));
        } catch {
          return ws.send(JSON.stringify({ type: 'error', code: 'bad_json', message: 'not JSON' }));
        }
        if (m.type === 'ping') return ws.send(JSON.stringify({ type: 'pong' }));
        if (m.type !== 'send' || typeof m.line !== 'string' || m.line.length > 80) {
          return ws.send(JSON.stringify({ type: 'error', code: 'bad_message', message: 'expected {type:"send", line}', id: m.id }));
        }
        await this.#ready;
        this.#broadcast({ type: 'sent', line: m.line, from: 'ws' });
        try {
          const replies = await this.client.command(m.line);
          if (m.id !== undefined) ws.send(JSON.stringify({ type: 'reply', id: m.id, lines: [...replies.map((r) => formatReply(r)), 'ok'] }));
        } catch (e) {
          if (m.id !== undefined) ws.send(JSON.stringify({ type: 'reply', id: m.id, lines: [`Error:${(e as Error).message}`, 'ok'] }));
        }
      });
    });
  }

  async #upload(id: number, text: string): Promise<void> {
    const job = this.#job!;
    const tell = () => this.#broadcast({ type: 'upload', id, bytesSent: job.bytesSent, bytesVerified: job.bytesVerified, bytesTotal: job.bytesTotal, state: job.state });
    try {
      await this.#ready;
      const file = `JOB${id}.UVJ`;
      await this.client.command(`M28 ${file}`);
      await this.client.stream(text.trimEnd().split('\n'), (sent, verified) => {
        job.bytesSent = sent;
        job.bytesVerified = verified;
        tell();
      });
      await this.client.command('M29');
      await this.client.command(`M23 ${file}`);
      await this.client.command('M24');
      job.state = 'started';
      tell();
    } catch (e) {
      job.state = 'failed';
      this.#broadcast({ type: 'upload', id, bytesSent: job.bytesSent, bytesVerified: job.bytesVerified, bytesTotal: job.bytesTotal, state: 'failed', error: (e as Error).message });
    }
  }

  #status() {
    const p = this.sim.printer;
    return {
      mega: 'online',
      firmware: 'UVExposure 0.1.0 (Simulated Mega)',
      position: { x: p.mega.motion.now()[0] / 1000, y: p.mega.motion.now()[1] / 1000, z: p.mega.motion.now()[2] / 1000 },
      temps: p.nano.deciC().map((d) => d / 10),
      limits: [0, 1, 2, 3, 4, 5].map((i) => Number(p.mega.config[`thermal.limit.${i}`])),
      job: this.#job ? { ...this.#job, stop: p.mega.job.done, stops: p.mega.job.plan?.count ?? 0 } : null,
      probe: p.nano.probe,
      faults: [],
      clients: this.#sockets.size,
    };
  }

  #broadcast(m: object): void {
    const s = JSON.stringify(m);
    for (const ws of this.#sockets) ws.send(s);
  }

  stop(): void {
    this.sim.stop();
  }
}
