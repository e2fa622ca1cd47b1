// What the app needs from a connected printer, whatever carries it: Web Serial, the ESP, or the simulated printer.

import type { Reply } from '../protocol/dialect-reply';
import type { PrintJob } from '../protocol/job-types';
import type { LinkHealth } from './dialect-client';
import type { TransportKind } from './transport';

export interface UploadProgress {
  bytesSent: number;
  bytesVerified: number;
  bytesTotal: number;
}

export interface PrinterLink {
  readonly kind: TransportKind;
  readonly health: LinkHealth;
  /** Printer seconds per wall second (the simulated printer may run faster than real time). */
  readonly timeScale: number;
  /** Every line the printer sends goes to `onReply`; `onClosed` fires once if the link drops. */
  open(onReply: (r: Reply, line: string) => void, onClosed: (error?: Error) => void): Promise<void>;
  /** One dialect line; resolves with its reply block, rejects with a CommandError. */
  command(line: string): Promise<Reply[]>;
  /** Uploads the job, verifies it on the printer, selects and starts it; `paced`: mega.md "Pacing". */
  startJob(job: PrintJob, onProgress: (p: UploadProgress) => void, opts?: StartOptions): Promise<void>;
  close(): Promise<void>;
}

export interface StartOptions {
  /** Run paced: the printer waits to cool before a stop or a pass rather than pause at a soft limit. */
  paced?: boolean;
}
