// Run-length rows (job.md "Run-length rows"): a format 2 job is never longer than format 1, and its records fit a line.
// That any row reads back to its cells is the firmware's to check: job.json's drawn runs, read by the C++ verifier.
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { encodeJob } from './job-encode';
import { runRecords } from './job-runs';
import { JOB_LIMITS, type PrintJob } from './job-types';

const job = (rows: number[][]): PrintJob => ({
  grid: { cols: rows[0].length, rows: rows.length }, pitchUm: { x: 50, y: 50 }, originUm: { x: 0, y: 0 },
  dose: { map: 'linear', fullUs: 1000 }, leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] }, strategy: { name: 'raster' }, gridData: rows,
});

// Rows of runs: values drawn from a few (0, 255, a gray) so that runs of every length occur.
const row = (cols: number) => fc.array(fc.record({ v: fc.constantFrom(0, 0, 255, 128, 7), n: fc.integer({ min: 1, max: 90 }) }), { minLength: 1, maxLength: 40 })
  .map((runs) => {
    const out: number[] = [];
    for (const { v, n } of runs) for (let i = 0; i < n && out.length < cols; i++) out.push(v);
    while (out.length < cols) out.push(0);
    return out;
  });

describe('run-length rows', () => {
  it('stay within 76 bytes, and are never longer than format 1', () => {
    fc.assert(fc.property(fc.integer({ min: 1, max: 700 }).chain((cols) => fc.array(row(cols), { minLength: 1, maxLength: 4 })), (rows) => {
      const text = encodeJob(job(rows), 2);
      for (const line of text.split('\n')) expect(line.length).toBeLessThanOrEqual(JOB_LIMITS.maxRecordBytes);
      expect(text.length).toBeLessThanOrEqual(encodeJob(job(rows), 1).length);
    }), { numRuns: 300 });
  });

  it('write a filled row of 600 as one run, and skip its zeros at both ends', () => {
    expect(runRecords(7, [0, 0, ...Array(600).fill(255), 0])).toEqual(['rl 7 2 600xff']);
    expect(runRecords(0, [0, 0, 0])).toEqual([]);
  });

  it('bridge a gap of zeros inside a record, and never start or end a record with one', () => {
    expect(runRecords(1, [9, 9, 9, 9, ...Array(40).fill(0), 5])).toEqual(['rl 1 0 4x09 40x00 05']);
  });
});
