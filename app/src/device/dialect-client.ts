// The host side of protocol/mega.md over a byte transport: the wait for the Mega's `start`, numbered,
// checksummed lines sent through the Mega's receive window, replies matched by the `ok N` field, resend
// and time-out recovery, link health.

import { DIALECT_MAX_LINE, encodeFrame } from '../protocol/dialect-frame';
import { parseReply, type Reply } from '../protocol/dialect-reply';
import { LineSplitter } from '../protocol/line-splitter';
import { CommandError } from './command-error';
import type { Transport } from './transport';

export interface LinkHealth {
  linesSent: number;
  bytesSent: number;
  resends: number;
  timeouts: number;
  bytesRetransmitted: number;
  /** Smoothed time from a line's first send to its acceptance, ms. */
  rttMs: number;
}

/** Commands that take longer than a round trip on the Mega (mega.md §5, "Long"). */
const LONG_COMMANDS = /^(G28|G29|G30|G4|M400|M18|M84|M822)(\s|$)/i;

interface Item {
  body: string;
  n: number;
  frame: string;
  firstSentMs: number;
  sent: boolean;
  resolve?: (payload: Reply[]) => void;
  reject?: (e: Error) => void;
  /** Counted by upload progress when accepted. */
  bytes: number;
  onAccepted?: () => void;
  onSent?: (bytes: number) => void;
}

export interface ClientOptions {
  /** Never more lines out than this, whatever the Mega advertises (1 = one line per ok). */
  maxWindow?: number;
  /** No reply for this long while lines are out: resend from the last accepted line. */
  replyTimeoutMs?: number;
  /** How long to wait for the Mega's `start` after the link opens before the first line goes anyway (a board the port did not reset). */
  startTimeoutMs?: number;
  now?: () => number;
  setTimer?: (fn: () => void, ms: number) => unknown;
  clearTimer?: (t: unknown) => void;
}

export class DialectClient {
  #busySinceOk = false;
  readonly health: LinkHealth = { linesSent: 0, bytesSent: 0, resends: 0, timeouts: 0, bytesRetransmitted: 0, rttMs: 0 };
  /** Lines the Mega may hold unanswered; 1 until M115 advertises its window. */
  window = 1;
  #splitter = new LineSplitter(4096);
  #waiting: Item[] = [];   // not yet numbered
  #out: Item[] = [];       // numbered, sent or due for a resend, ascending n
  #inflight = 0;
  #next = 1;
  #lastAccepted = 0;
  #block: Reply[] = [];
  #closed: Error | null = null;
  #timer: unknown = null;
  #lastReplyMs = 0;
  /** Ends the wait for `start`, while the link is opening. */
  #started: (() => void) | null = null;
  readonly #o: Required<ClientOptions>;

  constructor(private readonly transport: Transport, private readonly onReply: (r: Reply, line: string) => void, o: ClientOptions = {}) {
    this.#o = {
      maxWindow: o.maxWindow ?? 32,
      replyTimeoutMs: o.replyTimeoutMs ?? 3000, // above the Mega's 2 s busy: keep-alive
      // The bootloader's wait, then the firmware's set-up with up to 2 s for a card to leave idle (sd_storage.cpp).
      startTimeoutMs: o.startTimeoutMs ?? 5000,
      now: o.now ?? (() => performance.now()),
      setTimer: o.setTimer ?? ((fn, ms) => setTimeout(fn, ms)),
      clearTimer: o.clearTimer ?? ((t) => clearTimeout(t as ReturnType<typeof setTimeout>)),
    };
  }

  /**
   * Opens the link and waits for the Mega's `start` before the first line. Opening its USB port resets
   * it (DTR): its bootloader waits, then the firmware sets up and says `start`, and bytes sent before
   * that are lost, so a line sent at once would only come back as a time-out. The simulated printer
   * answers once its worker has loaded the firmware and read its card. As Marlin hosts do, a board
   * that says nothing (its port did not reset it) gets the first line after `startTimeoutMs`.
   */
  async open(onClosed: (error?: Error) => void): Promise<void> {
    const started = new Promise<void>((resolve) => {
      const timer = this.#o.setTimer(() => this.#started?.(), this.#o.startTimeoutMs);
      this.#started = () => {
        this.#o.clearTimer(timer);
        this.#started = null;
        resolve();
      };
    });
    try {
      await this.transport.open((bytes) => this.receive(bytes), (error) => {
        this.#fail(error ?? new Error('link closed'));
        onClosed(error);
      });
    } catch (e) {
      this.#started?.();
      throw e;
    }
    await started;
    await this.resync();
  }

  /** Sets the Mega's line number to 0 (after connecting or a reset). */
  async resync(): Promise<void> {
    this.#next = 0;
    this.#lastAccepted = -1;
    await this.command('M110 N0');
  }

  async close(): Promise<void> {
    this.#fail(new Error('closed'));
    await this.transport.close();
  }

  /** Sends one dialect line; resolves with the lines of its reply block once it is accepted. */
  command(body: string): Promise<Reply[]> {
    if (this.#closed) return Promise.reject(this.#closed);
    if (encodeFrame(this.#next + 1_000_000, body).length > DIALECT_MAX_LINE) return Promise.reject(new Error("line too long for the dialect"));
    return new Promise((resolve, reject) => {
      this.#waiting.push({ body, n: -1, frame: '', firstSentMs: 0, sent: false, resolve, reject, bytes: 0 });
      this.#pump();
    });
  }

  /**
   * Streams lines (job records) through the window without a promise each; `onProgress` gets the
   * bytes sent and the bytes the Mega accepted. Resolves when all are accepted.
   */
  stream(lines: string[], onProgress: (sentBytes: number, acceptedBytes: number) => void): Promise<void> {
    if (this.#closed) return Promise.reject(this.#closed);
    let sent = 0, accepted = 0, left = lines.length;
    return new Promise((resolve, reject) => {
      if (left === 0) return resolve();
      for (const body of lines) {
        const item: Item = { body, n: -1, frame: '', firstSentMs: 0, sent: false, bytes: 0 };
        item.onAccepted = () => {
          accepted += body.length + 1; // job bytes, as bytesTotal counts them
          onProgress(sent, accepted);
          if (--left === 0) resolve();
        };
        item.onSent = (b) => {
          sent += b;
          onProgress(sent, accepted);
        };
        item.reject = reject;
        this.#waiting.push(item);
      }
      this.#pump();
    });
  }

  receive(bytes: string): void {
    for (const { text } of this.#splitter.push(bytes)) {
      const r = parseReply(text);
      if (!r) continue;
      // Only answers to our lines (and the keep-alive of a long command) show the Mega is working
      // through them; auto-reports arrive every second whether or not our lines were lost.
      if (r.kind === 'ok' || r.kind === 'error' || r.kind === 'resend' || r.kind === 'busy') this.#lastReplyMs = this.#o.now();
      // A Mega that says busy is working on a line (a long command, a streamed record waiting for
      // room): wait for its keep-alive, not for the round trip, until the next ok.
      if (r.kind === 'busy') this.#busySinceOk = true;
      else if (r.kind === 'ok') this.#busySinceOk = false;
      else if (r.kind === 'start') this.#started?.();
      this.onReply(r, text);
      if (r.kind === 'cap' && r.name === 'RX_WINDOW') this.window = Math.max(1, Math.min(r.value, this.#o.maxWindow));
      if (r.kind === 'ok') this.#endBlock(r);
      else if (r.kind === 'resend') this.#resend(r.n);
      else this.#block.push(r);
    }
    this.#pump();
  }

  #endBlock(ok: Extract<Reply, { kind: 'ok' }>): void {
    this.#inflight = Math.max(0, this.#inflight - 1);
    if (ok.n === undefined || ok.n <= this.#lastAccepted) {
      // A skipped line, a resend request, an old duplicate, or an ok whose checksum failed: it ends
      // no command's reply. The lines before it stay in the block: a resent line still running gets
      // its ok at once, in the middle of the running line's own reply (an M503 listing: mega.md §2),
      // which was cut there before. Once every line sent has been answered, any still unconfirmed
      // goes again now rather than after the time-out: the Mega confirms a duplicate (ok N<n>)
      // without running it twice.
      if (this.#inflight === 0 && this.#out.some((i) => i.sent)) this.#rewindTo(this.#lastAccepted + 1);
      return;
    }
    const block = this.#block;
    this.#block = [];
    // N names the line this block answers; lines run in order, so all before it are done too.
    const now = this.#o.now();
    while (this.#out.length && this.#out[0].n <= ok.n) {
      const item = this.#out.shift()!;
      const ran = item.n === ok.n;
      const rtt = now - item.firstSentMs;
      this.health.rttMs = this.health.rttMs ? this.health.rttMs * 0.9 + rtt * 0.1 : rtt;
      // Line-level errors (codes 1-6) are the receiver's own replies; when a lost ok merged their block
      // into this one, they say nothing about the command.
      const err = ran ? block.find((x): x is Extract<Reply, { kind: 'error' }> => x.kind === 'error' && (x.code < 1 || x.code > 6)) : undefined;
      if (err && item.resolve) item.reject?.(new CommandError(err.code, err.message));
      else item.resolve?.(ran ? block : []);
      item.onAccepted?.();
    }
    this.#lastAccepted = ok.n;
  }

  #resend(n: number): void {
    if (n <= this.#lastAccepted) return;
    this.health.resends++;
    this.#rewindTo(n);
  }

  /** Every numbered line from `n` on goes out again, in order (duplicates are never run twice). */
  #rewindTo(n: number): void {
    for (const item of this.#out) {
      if (item.n >= n && item.sent) item.sent = false;
    }
  }

  #pump(): void {
    if (this.#closed) return;
    while (this.#inflight < this.window) {
      let item = this.#out.find((i) => !i.sent);
      if (!item) {
        const w = this.#waiting.shift();
        if (!w) break;
        w.n = this.#next++;
        w.frame = encodeFrame(w.n, w.body) + '\n';
        w.bytes = w.frame.length;
        this.#out.push(w);
        item = w;
      } else {
        this.health.bytesRetransmitted += item.frame.length;
      }
      if (!item.firstSentMs) item.firstSentMs = this.#o.now();
      // A line sent when none was owed an answer: the wait for one starts now, not at the last
      // reply, however long the link was quiet before it.
      if (!this.#waitingForReplies()) this.#lastReplyMs = this.#o.now();
      item.sent = true;
      this.#inflight++;
      this.health.linesSent++;
      this.health.bytesSent += item.frame.length;
      item.onSent?.(item.body.length + 1);
      this.transport.send(item.frame).catch((e) => this.#fail(e as Error));
    }
    this.#armTimer();
  }

  /** Lines out, or replies still owed: a lost reply can leave either without anything to wake us. */
  #waitingForReplies(): boolean {
    return this.#inflight > 0 || this.#out.some((i) => i.sent);
  }

  /**
   * How long to wait for a reply: about four round trips (at least 250 ms), or the full time-out
   * while a long command is out. Resending early is safe: a duplicate of a line still running only
   * frees its slot (mega.md §2). Until a first round trip is measured there is nothing to adapt to:
   * 1 s, as TCP starts with (RFC 6298), not a guess at the fastest link.
   */
  #timeoutMs(): number {
    if (this.#busySinceOk || this.#out.some((i) => i.sent && LONG_COMMANDS.test(i.body))) return this.#o.replyTimeoutMs;
    return Math.min(this.#o.replyTimeoutMs, this.health.rttMs ? Math.max(250, 4 * this.health.rttMs) : 1000);
  }

  #armTimer(): void {
    if (this.#timer !== null) return;
    if (this.#closed || !this.#waitingForReplies()) return;
    this.#lastReplyMs = this.#lastReplyMs || this.#o.now();
    this.#timer = this.#o.setTimer(() => this.#onTimer(), this.#timeoutMs());
  }

  #onTimer(): void {
    this.#timer = null;
    if (this.#closed || !this.#waitingForReplies()) return;
    const remaining = this.#timeoutMs() - (this.#o.now() - this.#lastReplyMs);
    if (remaining < 1) { // within a millisecond counts as expired: never re-arm for a sliver of time
      // Lost bytes took a line or its reply: start again after the last accepted line. The lines
      // heard since the last ok stay: they are the reply of the oldest line not yet answered (a long
      // one such as M503's listing, slower than the time-out on a busy page), whose ok is to come.
      this.health.timeouts++;
      this.#inflight = 0;
      this.#rewindTo(this.#lastAccepted + 1);
      this.#lastReplyMs = this.#o.now();
      this.#pump();
      return;
    }
    this.#timer = this.#o.setTimer(() => this.#onTimer(), remaining);
  }

  #fail(error: Error): void {
    if (this.#closed) return;
    this.#closed = error;
    this.#started?.(); // the first line then fails with the link
    if (this.#timer !== null) this.#o.clearTimer(this.#timer);
    for (const item of [...this.#out, ...this.#waiting]) item.reject?.(error);
    this.#out = [];
    this.#waiting = [];
  }
}
