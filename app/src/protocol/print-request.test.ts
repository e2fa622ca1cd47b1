import { describe, expect, it } from 'vitest';
import { encodeJob } from './job-encode';
import { ESP_LIMITS, validatePrintRequest } from './print-request';
import { cases, loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('esp.json');
const count = vectorCounter('esp.json');

describe('ESP POST /print vectors', () => {
  it('agrees on limits', () => {
    expect(ESP_LIMITS).toEqual({ maxBody: v.maxBody, maxCells: v.maxCells });
    count();
  });

  it.each(cases(v.requests, 'name'))('%s', (_n, c: any) => {
    const r = validatePrintRequest(c.body);
    expect(r.status).toBe(c.status);
    if (r.status === 202) {
      expect(encodeJob(r.job)).toBe(c.text);
      expect(r.paced).toBe(c.paced); // beside the job, never in its text
    } else {
      expect(r.error).toBe(c.error);
      if ('path' in c) expect(r.path).toBe(c.path);
    }
    count();
  });

  it('refuses an oversized body from its Content-Length before parsing', () => {
    expect(validatePrintRequest('{', ESP_LIMITS.maxBody + 1)).toMatchObject({ status: 413, error: 'too_large' });
  });
});
