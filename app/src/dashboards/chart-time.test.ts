import { describe, expect, it } from 'vitest';
import { agoLabel, minutesAgo } from './chart-time';

describe('the thermal chart\'s time axis', () => {
  it('counts minutes back from the newest sample', () => {
    expect(minutesAgo([100, 160, 400])).toEqual([-5, -4, 0]);
    expect(minutesAgo([])).toEqual([]);
  });
  it('reads as minutes, seconds under a minute, and now', () => {
    expect(agoLabel(0)).toBe('now');
    expect(agoLabel(-0.5)).toBe('-30 s');
    expect(agoLabel(-2)).toBe('-2 min');
    expect(agoLabel(-12.25)).toBe('-12.3 min');
  });
});
