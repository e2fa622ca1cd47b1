// A job's upload size as the question and the progress say it: its bytes as the printer's job format writes
// them (job.md) and on the wire, each record framed as a numbered mega.md line.

import { encodeFrame } from '../protocol/dialect-frame';
import { encodeJobRecords } from '../protocol/job-encode';
import type { JobFormat, PrintJob } from '../protocol/job-types';

export interface UploadSize {
  format: JobFormat;
  records: number;
  /** The job text's bytes, as the card stores them. */
  textBytes: number;
  /** The bytes the upload puts on the wire: each record as a numbered line with its checks. */
  wireBytes: number;
  cells: number;
}

/** The job's bytes as `format` writes them, and on the wire, numbered from line 1 as the app's client does after M110. */
export function uploadSize(job: PrintJob, format: JobFormat): UploadSize {
  let records = 0, textBytes = 0, wireBytes = 0;
  encodeJobRecords(job, (record) => {
    records++;
    textBytes += record.length + 1;
    wireBytes += encodeFrame(records, record).length + 1;
  }, format);
  return { format, records, textBytes, wireBytes, cells: job.grid.cols * job.grid.rows };
}

