// A paced job's times are its paced forecast's: the estimate it is held to, and what is left.
import { describe, expect, it } from 'vitest';
import { duration, estimateUsFor, leftS } from './job-times';

const HOUR = 3600e6;
const offered = { estimateUs: 1.25 * HOUR, pacedUs: 1.53 * HOUR }; // 1 h 15 min, paced 1 h 31 min 48 s

describe('job times', () => {
  it('holds a paced job to its paced estimate, an unpaced one to the plain estimate', () => {
    expect(estimateUsFor(offered, true)).toBe(offered.pacedUs);
    expect(estimateUsFor(offered, false)).toBe(offered.estimateUs);
    expect(estimateUsFor({ estimateUs: 5e6, pacedUs: null }, true)).toBe(5e6); // paced without a forecast
    expect(estimateUsFor(null, true)).toBeNull();
  });

  it("stretches the Mega's remaining time by the paced share of waits, and leaves it alone otherwise", () => {
    expect(leftS(4500, offered, true)).toBe(5508); // at the start: the whole paced time
    expect(leftS(0, offered, true)).toBe(0);
    expect(leftS(600, offered, false)).toBe(600);
    expect(leftS(600, { estimateUs: 5e6, pacedUs: null }, true)).toBe(600);
    expect(leftS(600, null, true)).toBe(600);
  });

  it('says durations in hours and minutes, minutes and seconds, or seconds', () => {
    expect(duration(5508)).toBe('1 h 32 min');
    expect(duration(4500)).toBe('1 h 15 min');
    expect(duration(7190)).toBe('2 h 0 min');
    expect(duration(245)).toBe('4 min 5 s');
    expect(duration(12)).toBe('12 s');
  });
});
