// What the app needs from a connected printer, whatever carries it: Web Serial, the ESP, or the simulated printer.

import type { Reply } from '../protocol/dialect-reply';
import type { PrintJob } from '../protocol/job-types';
import type { LinkHealth } from './dialect-client';
import type { TransportKind } from './transport';
import type { JobFormat } from '../protocol/job-types';
import type { LinkRate } from '../job/link-rate';

export interface UploadProgress {
  bytesSent: number;
  bytesVerified: number;
  bytesTotal: number;
  /** The upload's wire bytes sent so far and in all (numbered lines with their checks), where the link counts them. */
  wireSent?: number;
  wireTotal?: number;
  /** The wire bytes per second of the printer's time so far in this upload, once measurable. */
  bytesPerS?: number;
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
  /** The newest job format (job.md) the printer reads through this link. */
  readonly jobFormat: JobFormat;
  /** The printhead link's speed the printer plans jobs at (`Cap:LINK_BAUD` in M115, mega.md); null if it did not say. */
  readonly linkBaud: number | null;
  /** The upload rate: measured on the last upload through this link, else the line's. */
  readonly uploadRate: LinkRate;
  /** Uploads the job, verifies it on the printer, selects and starts it; `paced`: mega.md "Pacing". */
  startJob(job: PrintJob, onProgress: (p: UploadProgress) => void, opts?: StartOptions): Promise<void>;
  close(): Promise<void>;
}

export interface StartOptions {
  /** Run paced: the printer waits to cool before a stop or a pass rather than pause at a soft limit. */
  paced?: boolean;
}

/** A `Cap:<name>:<n>` value of an `M115` reply block (mega.md), or null when the printer did not say. */
export function capValue(info: readonly Reply[], name: string): number | null {
  const cap = info.find((r) => r.kind === 'cap' && r.name === name);
  return cap?.kind === 'cap' ? cap.value : null;
}
