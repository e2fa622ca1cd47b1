// Speaks the Mega dialect over a Transport: numbered, checksummed commands matched to their replies,
// and every report folded into one typed device state.

import { encodeFrame, DIALECT_MAX_LINE } from '../protocol/dialect-frame';
import { parseReply, type Reply } from '../protocol/dialect-reply';
import { LineSplitter } from '../protocol/line-splitter';
import type { Transport } from './transport';

export interface DeviceReport {
  firmware?: string;
  window?: number;
  deciC?: number[];
  limitDeciC?: number[];
}

export class CommandError extends Error {
  constructor(readonly code: number, message: string) {
    super(message);
  }
}

interface Pending {
  n: number;
  body: string;
  payload: Reply[];
  /** A Resend for this line came; the ok closing that error block is not this line's answer. */
  resent: boolean;
  resolve: (payload: Reply[]) => void;
  reject: (e: Error) => void;
  timer: ReturnType<typeof setTimeout>;
}

const REPLY_TIMEOUT_MS = 2000;
const MAX_RETRIES = 3;

/** One line in flight at a time; the windowed sender for job uploads builds on this. */
export class PrinterClient {
  readonly #splitter = new LineSplitter(4096);
  #next = 1;
  #queue: { body: string; resolve: Pending['resolve']; reject: Pending['reject'] }[] = [];
  #pending: Pending | null = null;
  #retries = 0;
  #closed = false;

  constructor(private readonly transport: Transport, private readonly onReport: (r: DeviceReport) => void) {}

  async open(onClosed: (error?: Error) => void): Promise<void> {
    await this.transport.open((bytes) => this.#receive(bytes), (error) => {
      this.#fail(error ?? new Error('link closed'));
      onClosed(error);
    });
    await this.command('M110 N0');
    this.#next = 1;
  }

  async close(): Promise<void> {
    this.#fail(new Error('closed'));
    await this.transport.close();
  }

  /** Sends one command; resolves with its payload lines once its `ok` arrives. */
  command(body: string): Promise<Reply[]> {
    if (this.#closed) return Promise.reject(new Error('not connected'));
    if (body.length + 20 > DIALECT_MAX_LINE) return Promise.reject(new Error('command too long'));
    return new Promise((resolve, reject) => {
      this.#queue.push({ body, resolve, reject });
      this.#pump();
    });
  }

  #pump(): void {
    if (this.#pending || this.#queue.length === 0) return;
    const { body, resolve, reject } = this.#queue.shift()!;
    const isReset = body.startsWith('M110');
    const n = isReset ? 0 : this.#next++;
    this.#pending = { n, body, payload: [], resent: false, resolve, reject, timer: setTimeout(() => this.#timeout(), REPLY_TIMEOUT_MS) };
    this.#retries = 0;
    void this.#write(n, body);
  }

  async #write(n: number, body: string): Promise<void> {
    try {
      await this.transport.send(encodeFrame(n, body) + '\n');
    } catch (e) {
      this.#fail(e as Error);
    }
  }

  #timeout(): void {
    const p = this.#pending;
    if (!p) return;
    if (++this.#retries > MAX_RETRIES) {
      this.#pending = null;
      p.reject(new Error(`no reply to ${p.body}`));
      this.#pump();
      return;
    }
    p.timer = setTimeout(() => this.#timeout(), REPLY_TIMEOUT_MS);
    void this.#write(p.n, p.body); // a duplicate is acknowledged, never run twice
  }

  #receive(bytes: string): void {
    for (const { text } of this.#splitter.push(bytes)) {
      const reply = parseReply(text);
      if (reply) this.#handle(reply);
    }
  }

  #handle(r: Reply): void {
    switch (r.kind) {
      case 'temps':
        this.onReport({ deciC: r.deciC, limitDeciC: r.limitDeciC });
        break;
      case 'firmware':
        this.onReport({ firmware: r.name });
        break;
      case 'cap':
        if (r.name === 'RX_WINDOW') this.onReport({ window: r.value });
        break;
      case 'resend': {
        const p = this.#pending;
        if (p && r.n === p.n) {
          p.resent = true;
          p.payload = [];
          void this.#write(p.n, p.body);
        }
        return;
      }
    }
    const p = this.#pending;
    if (!p) return;
    if (r.kind === 'ok') {
      if (p.resent) {
        p.resent = false;
        return; // the ok that closes the resend request; the resent line's own ok follows
      }
      clearTimeout(p.timer);
      this.#pending = null;
      const error = p.payload.find((x): x is Extract<Reply, { kind: 'error' }> => x.kind === 'error');
      if (error) p.reject(new CommandError(error.code, error.message));
      else p.resolve(p.payload);
      this.#pump();
    } else {
      p.payload.push(r);
    }
  }

  #fail(error: Error): void {
    this.#closed = true;
    if (this.#pending) {
      clearTimeout(this.#pending.timer);
      this.#pending.reject(error);
      this.#pending = null;
    }
    for (const q of this.#queue.splice(0)) q.reject(error);
  }
}
