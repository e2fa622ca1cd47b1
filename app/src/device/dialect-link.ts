// PrinterLink over a byte transport (Web Serial, the simulated printer): the windowed dialect client plus the
// job upload of protocol/mega.md (M28 … M29, then M23 and M24).

import type { Reply } from '../protocol/dialect-reply';
import type { JobFormat, PrintJob } from '../protocol/job-types';
import { CommandError } from './command-error';
import { encodeFrame } from '../protocol/dialect-frame';
import { encodeJob } from '../protocol/job-encode'; // in the dialect's file: as a file of its own it took a block of the ESP's flash
import { LINE_RATE, type LinkRate } from '../job/link-rate';
import { DialectClient, type ClientOptions, type LinkHealth } from './dialect-client';
import { capValue, type PrinterLink, type StartOptions, type UploadProgress } from './link';
import type { Transport } from './transport';

const UPLOAD_ATTEMPTS = 5;
/**
 * The Mega pauses a running job when no host has said anything for 30 s of its time (mega.md §6:
 * a host that went away). The app's reports come by themselves (M155, M154, M27 S), so it says
 * something on purpose: an M105 every 10 s of the printer's time, as Marlin hosts poll.
 */
export const HEARTBEAT_MS = 10_000;
const RETRY_CODES = [0, 21, 23, 24, 25, 26];

export class DialectLink implements PrinterLink {
  readonly kind;
  #client: DialectClient;
  #jobs = 0;
  #heartbeat: unknown = null;
  /** The newest job format the printer reads (`Cap:JOB_FORMAT`, mega.md); 1 for firmware that does not say. */
  jobFormat: JobFormat = 1;
  /** The printhead link's speed the printer plans jobs at (`Cap:LINK_BAUD`, mega.md); null for firmware that does not say. */
  linkBaud: number | null = null;
  /** Wire bytes per second of the printer's time on the last whole upload through this link. */
  uploadRate: LinkRate = LINE_RATE;

  constructor(private readonly transport: Transport, private readonly clientOptions: ClientOptions = {}) {
    this.kind = transport.kind;
    this.#client = new DialectClient(transport, (r, line) => this.#onReply(r, line), clientOptions);
  }

  #onReply: (r: Reply, line: string) => void = () => {};

  get timeScale(): number {
    return this.transport.timeScale ?? 1;
  }

  get health(): LinkHealth {
    return this.#client.health;
  }

  async open(onReply: (r: Reply, line: string) => void, onClosed: (error?: Error) => void): Promise<void> {
    this.#onReply = onReply;
    await this.#client.open((error) => {
      this.#stopHeartbeat();
      this.transport.onRescaled = null;
      onClosed(error);
    });
    const info = await this.#client.command('M115'); // learns the receive window and the job format
    const cap = info.find((r) => r.kind === 'cap' && r.name === 'JOB_FORMAT');
    this.jobFormat = cap?.kind === 'cap' && cap.value >= 2 ? 2 : 1;
    this.linkBaud = capValue(info, 'LINK_BAUD');
    this.#beat();
    this.transport.onRescaled = () => { // the next heartbeat at the new speed's period, from now
      this.#stopHeartbeat();
      this.#beat();
    };
  }

  /** The next heartbeat, in the client's clock (the printer's own, or the page's at its speed-up). */
  #beat(): void {
    const set = this.clientOptions.setTimer ?? ((fn: () => void, ms: number) => setTimeout(fn, ms));
    this.#heartbeat = set(() => {
      this.#client.command('M105').catch(() => {}); // a refusal or a lost link is said elsewhere
      this.#beat();
    }, HEARTBEAT_MS / this.timeScale);
  }

  #stopHeartbeat(): void {
    if (this.#heartbeat === null) return;
    const clear = this.clientOptions.clearTimer ?? ((t: unknown) => clearTimeout(t as ReturnType<typeof setTimeout>));
    clear(this.#heartbeat);
    this.#heartbeat = null;
  }

  command(line: string): Promise<Reply[]> {
    return this.#client.command(line);
  }

  async startJob(job: PrintJob, onProgress: (p: UploadProgress) => void, opts: StartOptions = {}): Promise<void> {
    const pace = opts.paced ? ' P1' : '';
    const text = encodeJob(job, this.jobFormat);
    const records = text.trimEnd().split('\n');
    const total = records.reduce((n, r) => n + r.length + 1, 0);
    const wireTotal = records.reduce((n, r, i) => n + encodeFrame(i + 1, r).length + 1, 0);
    const now = this.clientOptions.now ?? (() => performance.now());
    // The printer's seconds since `t0`: the client's clock is the page's, the printer runs timeScale of them a second.
    const since = (t0: number) => ((now() - t0) / 1000) * (this.clientOptions.now ? 1 : this.timeScale);
    let sentBefore = 0;
    let streaming = false;
    for (let attempt = 1; ; attempt++) {
      const file = `${(job.name ?? 'job').replace(/[^A-Za-z0-9_-]/g, '').slice(0, 20) || 'job'}-${++this.#jobs}.uvj`;
      try {
        onProgress({ bytesSent: sentBefore, bytesVerified: 0, bytesTotal: total, wireSent: 0, wireTotal });
        streaming = await this.#openUpload(file, pace);
        let sent = 0;
        const t0 = now();
        const w0 = this.#client.health.bytesSent; // whole lines, resends included
        const wire = () => this.#client.health.bytesSent - w0;
        const rate = () => {
          const s = since(t0);
          return s > 0.25 ? wire() / s : undefined;
        };
        await this.#client.stream(records, (s, accepted) => {
          sent = s;
          onProgress({ bytesSent: sentBefore + s, bytesVerified: accepted, bytesTotal: total, wireSent: wire(), wireTotal, bytesPerS: rate() });
        });
        sentBefore += sent;
        const bytesPerS = rate(); // to the last record's ok: M29's checking and planning are the printer's, not the link's
        await this.#client.command('M29'); // the Mega checks every record and the whole-job CRC
        if (bytesPerS) this.uploadRate = { bytesPerS, measured: true };
        onProgress({ bytesSent: sentBefore, bytesVerified: total, bytesTotal: total, wireSent: wireTotal, wireTotal, bytesPerS });
        if (streaming) return; // a stream is already exposing
        await this.#client.command(`M23 ${file}`);
        await this.#client.command(`M24${pace}`);
        return;
      } catch (e) {
        // On a noisy link a damaged line can slip past the 8-bit line checksum (mega.md): a bad record
        // fails the CRC at M29 and the Mega deletes the file (E23-E25), a damaged M23/M24 finds no file
        // or no job (E21, E26), a damaged error line has no code (E0). Nothing ran: do it all again.
        // A stream has exposed cells already: it is never sent twice.
        if (streaming || !(e instanceof CommandError) || !RETRY_CODES.includes(e.code) || attempt === UPLOAD_ATTEMPTS) throw e;
      }
    }
  }

  /** M28 to spool on the SD card; a Mega without one streams instead (M828), with no resume. True when streaming. */
  async #openUpload(file: string, pace: string): Promise<boolean> {
    try {
      await this.#client.command(`M28 ${file}`);
      return false;
    } catch (e) {
      if (!(e instanceof CommandError) || e.code !== 20) throw e;
    }
    await this.#client.command(`M828${pace}`);
    return true;
  }

  close(): Promise<void> {
    this.#stopHeartbeat();
    this.transport.onRescaled = null;
    return this.#client.close();
  }
}
