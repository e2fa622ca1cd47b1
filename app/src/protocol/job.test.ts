import { describe, expect, it } from 'vitest';
import { encodeJob } from './job-encode';
import { verifyJobText, type Segment } from './job-verify';
import { cases, loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('job.json');
const count = vectorCounter('job.json');

describe('job format vectors', () => {
  it.each(cases(v.jobs, 'name'))('%s: encodes byte-exact and verifies', (_n, c: any) => {
    const text = encodeJob(c.job, c.format ?? 1);
    expect(text).toBe(c.text);
    expect(text.endsWith(`end ${c.crc}\n`)).toBe(true);
    const cells = c.job.gridData.map((row: number[]) => row.map(() => 0));
    const { error, header } = verifyJobText(text, (s: Segment) => s.cells.forEach((x, i) => (cells[s.row][s.col + i] = x)));
    expect(error).toBeNull();
    expect(header).toMatchObject({ cols: c.job.grid.cols, rows: c.job.grid.rows });
    expect(cells).toEqual(c.job.gridData);
    count();
  });

  it.each(cases(v.invalid, 'why'))('%s: refused with its code, or 0 for the valid one beside them', (_w, c: any) => {
    const { error } = verifyJobText(c.text);
    expect(error?.code ?? 0).toBe(c.error);
    count();
  });
});
