import { describe, expect, it } from 'vitest';
import { agoLabel, secondsAgo, timeAxis } from './chart-time';

describe('the thermal chart\'s time axis', () => {
  it('counts seconds back from the newest sample', () => {
    expect(secondsAgo([100, 160, 400])).toEqual([-300, -240, 0]);
    expect(secondsAgo([])).toEqual([]);
  });

  it('reads as seconds, minutes, and now', () => {
    expect(agoLabel(0)).toBe('now');
    expect(agoLabel(-0.3)).toBe('now');
    expect(agoLabel(-30)).toBe('-30 s');
    expect(agoLabel(-120)).toBe('-2 min');
    expect(agoLabel(-150.4)).toBe('-2 min 30 s');
  });

  // Issue 29, item 12: at first the axis read "now, 20 min … 100 min", a few seconds later
  // "-3 s, -2 s, -2 s, -1 s, -1 s, now" under "minutes before now".
  it('labels the first seconds truthfully: a minute\'s window, every tick a different time, now last', () => {
    for (const historyS of [0, 1, 3, 59]) {
      const axis = timeAxis(historyS);
      expect(axis.spanS).toBe(60);
      expect(axis.ticks.map(agoLabel)).toEqual(['-1 min', '-45 s', '-30 s', '-15 s', 'now']);
    }
  });

  it('widens as the history grows, up to its 20 minutes, with distinct labels in order', () => {
    const seen: number[] = [];
    for (let historyS = 0; historyS <= 1500; historyS += 7) {
      const { spanS, ticks } = timeAxis(historyS);
      expect(spanS).toBeGreaterThanOrEqual(Math.min(historyS, 1200));
      expect(ticks[0]).toBe(-spanS);
      expect(ticks.at(-1)).toBe(0);
      expect(ticks.length).toBeGreaterThanOrEqual(5);
      expect(ticks.length).toBeLessThanOrEqual(6);
      const labels = ticks.map(agoLabel);
      expect(new Set(labels).size).toBe(labels.length);
      seen.push(spanS);
    }
    expect([...new Set(seen)]).toEqual([60, 120, 300, 600, 1200]);
    expect(timeAxis(1200).ticks.map(agoLabel)).toEqual(['-20 min', '-15 min', '-10 min', '-5 min', 'now']);
  });
});
