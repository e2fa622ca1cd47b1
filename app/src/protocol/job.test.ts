import { describe, expect, it } from 'vitest';
import { encodeJob } from './job-encode';
import { cases, loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('job.json');
const count = vectorCounter('job.json');

// The app writes job text and the firmware reads it: the jobs bind this encoder byte for byte, and the
// C++ verifier reads each back to its cells and refuses the invalid ones (firmware/common/protocol/test/job_test.cpp).
describe('job format vectors', () => {
  it.each(cases(v.jobs, 'name'))('%s: encodes byte-exact', (_n, c: any) => {
    const text = encodeJob(c.job, c.format ?? 1);
    expect(text).toBe(c.text);
    expect(text.endsWith(`end ${c.crc}\n`)).toBe(true);
    count();
  });
});
