// PrinterLink to the ESP (protocol/esp.md): jobs by POST /print, everything else over the /ws WebSocket.

import { LINE_RATE, type LinkRate } from '../job/link-rate';
import { parseReply, type Reply } from '../protocol/dialect-reply';
import type { JobFormat, PrintJob } from '../protocol/job-types';
import { CommandError } from './command-error';
import { postJob } from './esp-post';
import type { LinkHealth } from './dialect-client';
import { capValue, type PrinterLink, type StartOptions, type UploadProgress } from './link';

type FromEsp =
  | { type: 'hello'; protocol: number; firmware: string }
  | { type: 'line'; line: string }
  | { type: 'sent'; line: string; from: string }
  | { type: 'reply'; id: number; lines: string[] }
  | { type: 'upload'; id: number; bytesSent: number; bytesVerified: number; bytesTotal: number; state: 'uploading' | 'started' | 'failed'; error?: string }
  | { type: 'status' }
  | { type: 'error'; code: string; message: string; id?: number }
  | { type: 'pong' };

const COMMAND_TIMEOUT_MS = 30_000;

export class EspLink implements PrinterLink {
  readonly kind = 'esp' as const;
  /** The hub's Mega runs in real time. */
  readonly timeScale = 1;
  readonly health: LinkHealth = { linesSent: 0, bytesSent: 0, resends: 0, timeouts: 0, bytesRetransmitted: 0, rttMs: 0 };
  #ws: WebSocket | null = null;
  #id = 0;
  #pending = new Map<number, { resolve: (r: Reply[]) => void; reject: (e: Error) => void; sentMs: number; timer: ReturnType<typeof setTimeout> }>();
  #upload: ((m: Extract<FromEsp, { type: 'upload' }>) => void) | null = null;
  #closing = false;
  /** The hub builds the job text itself, in the newest format its Mega reads (`Cap:JOB_FORMAT` in the M115 reply, esp.md): its bytes are what the estimate counts. */
  jobFormat: JobFormat = 1;
  /** The Mega's printhead link speed for jobs (`Cap:LINK_BAUD` in the M115 reply); null if it did not say. */
  linkBaud: number | null = null;
  uploadRate: LinkRate = LINE_RATE;

  constructor(private readonly origin: string) {}

  async open(onReply: (r: Reply, line: string) => void, onClosed: (error?: Error) => void): Promise<void> {
    await this.#connect(onReply, onClosed);
    const info = await this.command('M115'); // the Mega's identity reaches us as relayed lines
    const cap = info.find((r) => r.kind === 'cap' && r.name === 'JOB_FORMAT');
    this.jobFormat = cap?.kind === 'cap' && cap.value >= 2 ? 2 : 1; // as the hub reads the same answer
    this.linkBaud = capValue(info, 'LINK_BAUD');
  }

  #connect(onReply: (r: Reply, line: string) => void, onClosed: (error?: Error) => void): Promise<void> {
    return new Promise((resolve, reject) => {
      const ws = new WebSocket(this.origin.replace(/^http/, 'ws') + '/ws');
      this.#ws = ws;
      let opened = false;
      ws.onopen = () => {
        opened = true;
        resolve();
      };
      ws.onerror = () => {
        if (!opened) reject(new Error('cannot reach the printer’s Wi-Fi hub'));
      };
      ws.onclose = () => {
        const error = new Error('the Wi-Fi hub closed the connection');
        for (const p of this.#pending.values()) {
          clearTimeout(p.timer);
          p.reject(error);
        }
        this.#pending.clear();
        if (opened && !this.#closing) onClosed(error);
      };
      ws.onmessage = (e) => {
        let m: FromEsp;
        try {
          m = JSON.parse(String(e.data));
        } catch {
          return;
        }
        switch (m.type) {
          case 'line': {
            const r = parseReply(m.line);
            if (r) onReply(r, m.line);
            break;
          }
          case 'reply': {
            const p = this.#pending.get(m.id);
            if (!p) break;
            this.#pending.delete(m.id);
            clearTimeout(p.timer);
            const rtt = performance.now() - p.sentMs;
            this.health.rttMs = this.health.rttMs ? this.health.rttMs * 0.9 + rtt * 0.1 : rtt;
            const replies = m.lines.map(parseReply).filter((r): r is Reply => r !== null);
            const err = replies.find((r): r is Extract<Reply, { kind: 'error' }> => r.kind === 'error');
            if (err) p.reject(new CommandError(err.code, err.message));
            else p.resolve(replies.filter((r) => r.kind !== 'ok'));
            break;
          }
          case 'error': {
            const p = m.id !== undefined ? this.#pending.get(m.id) : undefined;
            if (p && m.id !== undefined) {
              this.#pending.delete(m.id);
              clearTimeout(p.timer);
              p.reject(new Error(`${m.code}: ${m.message}`));
            }
            break;
          }
          case 'upload':
            this.#upload?.(m);
            break;
        }
      };
    });
  }

  command(line: string): Promise<Reply[]> {
    const ws = this.#ws;
    if (!ws || ws.readyState !== WebSocket.OPEN) return Promise.reject(new Error('not connected'));
    const id = ++this.#id;
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.#pending.delete(id);
        this.health.timeouts++;
        reject(new Error(`no reply to ${line}`));
      }, COMMAND_TIMEOUT_MS);
      this.#pending.set(id, { resolve, reject, sentMs: performance.now(), timer });
      const frame = JSON.stringify({ type: 'send', line, id });
      this.health.linesSent++;
      this.health.bytesSent += frame.length;
      ws.send(frame);
    });
  }

  async startJob(job: PrintJob, onProgress: (p: UploadProgress) => void, opts: StartOptions = {}): Promise<void> {
    const body = JSON.stringify({ ...job, ...(opts.paced ? { paced: true } : {}), gridData: job.gridData.map((row) => Array.from(row)) });
    let first: { ms: number; sent: number } | null = null;
    const done = new Promise<void>((resolve, reject) => {
      this.#upload = (m) => {
        // The rate from what the hub says it has sent to the Mega, between its first word and its last.
        const now = performance.now();
        first ??= { ms: now, sent: m.bytesSent };
        const s = (now - first.ms) / 1000;
        const bytesPerS = s >= 0.5 && m.bytesSent > first.sent ? (m.bytesSent - first.sent) / s : undefined;
        onProgress({ bytesSent: m.bytesSent, bytesVerified: m.bytesVerified, bytesTotal: m.bytesTotal, bytesPerS });
        if (m.state === 'started' && bytesPerS) this.uploadRate = { bytesPerS, measured: true, counts: 'text' }; // the hub counts job text
        if (m.state === 'started') resolve();
        if (m.state === 'failed') reject(new Error(m.error ?? 'upload failed'));
      };
    });
    const r = await postJob(`${this.origin}/print`, body);
    if (r.status !== 202) {
      this.#upload = null;
      let message = `HTTP ${r.status}`;
      try {
        const e = await r.json();
        message = `${e.error.code}: ${e.error.message}`;
      } catch {
        /* keep the status */
      }
      throw new Error(message);
    }
    await done;
    this.#upload = null;
  }

  async close(): Promise<void> {
    this.#closing = true;
    this.#ws?.close();
    this.#ws = null;
  }
}
