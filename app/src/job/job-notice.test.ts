import { describe, expect, it } from 'vitest';
import { jobEnd, pageTitle } from './job-notice';

describe('the end of a job', () => {
  const running = { state: 'running' as const, file: 'pcb-1.uvj', stop: 10, stops: 40 };
  it('is told once, when a running or paused job ends', () => {
    expect(jobEnd(running, { state: 'done', file: 'pcb-1.uvj', stop: 40, stops: 40 })).toEqual({ title: 'Job done', body: 'pcb-1.uvj: done, stop 40 of 40.' });
    expect(jobEnd({ ...running, state: 'paused' }, { state: 'aborted', stop: 12, stops: 40 })?.title).toBe('Job stopped');
    expect(jobEnd(running, { state: 'failed', reason: 'thermal', stop: 12, stops: 40 })?.body).toBe('The job: failed (thermal), stop 12 of 40.');
    expect(jobEnd(running, { ...running, stop: 11 })).toBeNull();
    expect(jobEnd({ state: 'done' }, { state: 'done' })).toBeNull(); // a report repeated
    expect(jobEnd(null, { state: 'done' })).toBeNull(); // connecting to a printer that finished earlier
  });
  it('names the page: progress, then the end while the job shows it, seen or not', () => {
    expect(pageTitle(running, null)).toBe('25 % exposing · UV Exposure');
    expect(pageTitle({ state: 'done' }, 'Job done')).toBe('Job done · UV Exposure');
    expect(pageTitle({ state: 'done' }, null)).toBe('Job done · UV Exposure'); // looked at: still said, as the job's line says it
    expect(pageTitle({ state: 'aborted', stop: 3, stops: 8 }, null)).toBe('Job stopped · UV Exposure');
    expect(pageTitle({ state: 'failed', reason: 'thermal' }, null)).toBe('Job failed · UV Exposure');
    expect(pageTitle(null, 'Job done')).toBe('Job done · UV Exposure'); // disconnected before it was seen
    expect(pageTitle({ state: 'paused', stop: 3, stops: 8 }, null)).toBe('Paused · UV Exposure');
    expect(pageTitle(null, null)).toBe('UV Exposure');
  });
});
