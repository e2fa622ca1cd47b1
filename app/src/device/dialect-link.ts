// PrinterLink over a byte transport (Web Serial, the simulated printer): the windowed dialect client plus the
// job upload of protocol/mega.md (M28 … M29, then M23 and M24).

import type { Reply } from '../protocol/dialect-reply';
import { encodeJob } from '../protocol/job-encode';
import type { PrintJob } from '../protocol/job-types';
import { DialectClient, type ClientOptions, type LinkHealth } from './dialect-client';
import type { PrinterLink, UploadProgress } from './link';
import type { Transport } from './transport';

export class DialectLink implements PrinterLink {
  readonly kind;
  #client: DialectClient;
  #jobs = 0;

  constructor(transport: Transport, private readonly clientOptions: ClientOptions = {}) {
    this.kind = transport.kind;
    this.#client = new DialectClient(transport, (r, line) => this.#onReply(r, line), clientOptions);
  }

  #onReply: (r: Reply, line: string) => void = () => {};

  get health(): LinkHealth {
    return this.#client.health;
  }

  async open(onReply: (r: Reply, line: string) => void, onClosed: (error?: Error) => void): Promise<void> {
    this.#onReply = onReply;
    await this.#client.open(onClosed);
    await this.#client.command('M115'); // learns the receive window
  }

  command(line: string): Promise<Reply[]> {
    return this.#client.command(line);
  }

  async startJob(job: PrintJob, onProgress: (p: UploadProgress) => void): Promise<void> {
    const text = encodeJob(job);
    const records = text.trimEnd().split('\n');
    const file = `${(job.name ?? 'job').replace(/[^A-Za-z0-9_-]/g, '').slice(0, 20) || 'job'}-${++this.#jobs}.uvj`;
    const total = records.reduce((n, r) => n + r.length + 1, 0);
    onProgress({ bytesSent: 0, bytesVerified: 0, bytesTotal: total });
    await this.#client.command(`M28 ${file}`);
    let verified = 0;
    await this.#client.stream(records, (sent, accepted) => {
      verified = accepted;
      onProgress({ bytesSent: sent, bytesVerified: accepted, bytesTotal: total });
    });
    await this.#client.command('M29'); // the Mega checks every record and the CRC; it rejects a bad upload
    onProgress({ bytesSent: verified, bytesVerified: total, bytesTotal: total });
    await this.#client.command(`M23 ${file}`);
    await this.#client.command('M24');
  }

  close(): Promise<void> {
    return this.#client.close();
  }
}
