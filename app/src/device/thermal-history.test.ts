import { describe, expect, it } from 'vitest';
import { HISTORY_S, ThermalHistory } from './thermal-history';

const temps = (v: number) => [v, v + 1, v + 2, v + 3, v + 4, v + 5];

describe('ThermalHistory', () => {
  it('keeps 20 minutes of once-a-second reports, oldest first, as columns', () => {
    const h = new ThermalHistory();
    for (let s = 0; s < 2 * HISTORY_S; s++) h.add(1000 + s, temps(s), false);
    const [t, t0, , , , , t5] = h.columns();
    expect(t.length).toBe(HISTORY_S + 1);
    expect(t[0]).toBe(1000 + 2 * HISTORY_S - 1 - HISTORY_S);
    expect(t.at(-1)).toBe(1000 + 2 * HISTORY_S - 1);
    expect(t0.at(-1)).toBe(2 * HISTORY_S - 1);
    expect(t5.at(-1)).toBe(2 * HISTORY_S - 1 + 5);
  });

  it('drops a report older than the newest, and keeps whether a job was exposing', () => {
    const h = new ThermalHistory(10);
    h.add(5, temps(20), true);
    h.add(4, temps(99), false);
    h.add(6, temps(21), false);
    expect(h.recent(60).map((s) => [s.tS, s.celsius[0], s.exposing])).toEqual([[5, 20, true], [6, 21, false]]);
    expect(h.recent(0).length).toBe(1);
  });
});
