import { describe, expect, it } from 'vitest';
import { resumeVerdict } from './resume';

const cp = { file: 'a.uvj', done: 7, stops: 20, boot: 3, fires: 40 };

describe('resumeVerdict', () => {
  it('runs the next stop when the Nano never lit it', () => {
    expect(resumeVerdict(cp, { op: 'C', boot: 3, fires: 40, whole: true })).toEqual({ from: 7, verdict: 'had not been sent' });
  });
  it('counts a stop the Nano finished alone while the Mega restarted', () => {
    expect(resumeVerdict(cp, { op: 'C', boot: 3, fires: 41, whole: true }).from).toBe(8);
  });
  it('exposes again a stop that was cut short, or that a restarted Nano may have cut', () => {
    expect(resumeVerdict(cp, { op: 'C', boot: 3, fires: 41, whole: false })).toEqual({ from: 7, verdict: 'was cut short, and is exposed again' });
    expect(resumeVerdict(cp, { op: 'C', boot: 4, fires: 0, whole: true }).verdict).toMatch(/printhead's restart/);
    expect(resumeVerdict(cp, null).from).toBe(7);
  });
});
