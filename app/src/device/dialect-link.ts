// PrinterLink over a byte transport (Web Serial, the simulated printer): the windowed dialect client plus the
// job upload of protocol/mega.md (M28 … M29, then M23 and M24).

import type { Reply } from '../protocol/dialect-reply';
import type { PrintJob } from '../protocol/job-types';
import { CommandError } from './command-error';
import { DialectClient, type ClientOptions, type LinkHealth } from './dialect-client';
import type { PrinterLink, StartOptions, UploadProgress } from './link';
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
    await this.#client.command('M115'); // learns the receive window
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
    const { encodeJob } = await import('../protocol/job-encode'); // loaded with the first job
    const text = encodeJob(job);
    const records = text.trimEnd().split('\n');
    const total = records.reduce((n, r) => n + r.length + 1, 0);
    let sentBefore = 0;
    let streaming = false;
    for (let attempt = 1; ; attempt++) {
      const file = `${(job.name ?? 'job').replace(/[^A-Za-z0-9_-]/g, '').slice(0, 20) || 'job'}-${++this.#jobs}.uvj`;
      try {
        onProgress({ bytesSent: sentBefore, bytesVerified: 0, bytesTotal: total });
        streaming = await this.#openUpload(file, pace);
        let sent = 0;
        await this.#client.stream(records, (s, accepted) => {
          sent = s;
          onProgress({ bytesSent: sentBefore + s, bytesVerified: accepted, bytesTotal: total });
        });
        sentBefore += sent;
        await this.#client.command('M29'); // the Mega checks every record and the whole-job CRC
        onProgress({ bytesSent: sentBefore, bytesVerified: total, bytesTotal: total });
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
