// Encodes a PrintJob as the canonical job text of protocol/job.md.

import { crc32Hex, crc32Update } from './crc32';
import { runRecords } from './job-runs';
import { JOB_LIMITS, type JobFormat, type PrintJob } from './job-types';

const HEX = Array.from({ length: 256 }, (_, i) => i.toString(16).padStart(2, '0'));

/** Canonical segments of one row: [startCol, endCol] inclusive (job.md "Cells"). */
export function rowSegments(row: ArrayLike<number>): [number, number][] {
  const out: [number, number][] = [];
  const n = row.length;
  let c = 0;
  while (c < n) {
    if (row[c] === 0) {
      c++;
      continue;
    }
    const start = c;
    let end = c;
    for (;;) {
      let next = end + 1;
      while (next < n && row[next] === 0) next++;
      if (next < n && next - end - 1 <= JOB_LIMITS.maxGap && next - start + 1 <= JOB_LIMITS.maxCellsPerRecord) end = next;
      else break;
    }
    out.push([start, end]);
    c = end + 1;
  }
  return out;
}

export function jobHeaderLines(job: PrintJob, format: JobFormat = 1): string[] {
  const d = job.dose;
  const gains = job.leds.gainPermille ?? [1000, 1000, 1000, 1000];
  const thermal = job.thermal ?? { coeffCentiPctPerC: 0, refDeciC: 250 };
  const seed = job.strategy.name === 'random' ? job.strategy.seed ?? 0 : 0;
  return [
    `uvj ${format}`,
    `grid ${job.grid.cols} ${job.grid.rows}`,
    `pitch ${job.pitchUm.x} ${job.pitchUm.y}`,
    `origin ${job.originUm.x} ${job.originUm.y}`,
    d.map === 'linear' ? 'map linear' : `map threshold ${d.level}`,
    'fullUs' in d ? `full ${d.fullUs}` : `target ${d.targetUJcm2} ${d.irradianceUWcm2.join(' ')}`,
    `gain ${gains.join(' ')}`,
    `thermal ${thermal.coeffCentiPctPerC} ${thermal.refDeciC}`,
    `leds ${job.leds.offsets.map(([dx, dy]) => `${dx} ${dy}`).join(' ')}`,
    `strategy ${job.strategy.name} ${seed}`,
  ];
}

/** The canonical `r` records of row `r` (format 1, and format 2 where they are not longer). */
export function segmentRecords(r: number, row: ArrayLike<number>): string[] {
  return rowSegments(row).map(([a, b]) => {
    let hex = '';
    for (let c = a; c <= b; c++) hex += HEX[row[c]];
    return `r ${r} ${a} ${hex}`;
  });
}

const bytes = (records: string[]) => records.reduce((n, s) => n + s.length + 1, 0);

/** A row's records: format 2 writes its `rl` records when they are shorter than its `r` records (job.md). */
export function rowRecords(r: number, row: ArrayLike<number>, format: JobFormat = 1): string[] {
  const segments = segmentRecords(r, row);
  if (format === 1 || segments.length === 0) return segments;
  const runs = runRecords(r, row);
  return bytes(runs) < bytes(segments) ? runs : segments;
}

/** Calls `emit` with each record (without '\n'), `end` last. */
export function encodeJobRecords(job: PrintJob, emit: (record: string) => void, format: JobFormat = 1): void {
  let crc = 0;
  const out = (line: string) => {
    crc = crc32Update(crc, line + '\n');
    emit(line);
  };
  for (const line of jobHeaderLines(job, format)) out(line);
  job.gridData.forEach((row, r) => {
    for (const record of rowRecords(r, row, format)) out(record);
  });
  emit(`end ${crc32Hex(crc)}`);
}

/** The job text; format 2 only for a printer that reads it (`Cap:JOB_FORMAT:2`, mega.md). */
export function encodeJob(job: PrintJob, format: JobFormat = 1): string {
  const parts: string[] = [];
  encodeJobRecords(job, (rec) => parts.push(rec + '\n'), format);
  return parts.join('');
}
