import { describe, expect, it } from 'vitest';
import { HEAD_THERMAL } from '../machine/head-thermal';
import { rateWarnings, type Sample } from './thermal-watch';

/** 30 s of reports, sensor k rising at rates[k] °C/s from the room's 23 °C. */
const run = (rates: number[], exposing: boolean): Sample[] =>
  Array.from({ length: 31 }, (_, s) => ({ tS: s, celsius: rates.map((r) => 23 + r * s), exposing }));

describe('rateWarnings', () => {
  it('says nothing of a machine at rest', () => {
    expect(rateWarnings(run([0, 0, 0, 0, 0, 0], false), null, HEAD_THERMAL)).toEqual([]);
  });

  it('flags an LED warming with no job lit', () => {
    const w = rateWarnings(run([0, 0, 0.5, 0, 0, 0], false), null, HEAD_THERMAL);
    expect(w.map((x) => x.sensor)).toEqual([2]);
    expect(w[0].observedCPerS).toBeCloseTo(0.5, 5);
    expect(w[0].expectedCPerS).toBe(0);
  });

  it('lets an exposing job explain what its duty explains, and no more', () => {
    // 20 % duty on every LED: 2.5 × 0.2 = 0.5 °C/s, less 0.08 × 3 of cooling at the mean 26 °C.
    const duty = [0.2, 0.2, 0.2, 0.2];
    expect(rateWarnings(run([0.2, 0.2, 0.2, 0.2, 0, 0], true), duty, HEAD_THERMAL)).toEqual([]);
    const w = rateWarnings(run([0.2, 0.2, 0.2, 1.5, 0, 0], true), duty, HEAD_THERMAL);
    expect(w.map((x) => x.sensor)).toEqual([3]);
  });

  it('flags the driver or the frame warming beyond the model', () => {
    expect(rateWarnings(run([0, 0, 0, 0, 0.4, 0.3], false), null, HEAD_THERMAL).map((x) => x.sensor)).toEqual([4, 5]);
  });

  it('waits for 10 s of reports before it judges', () => {
    expect(rateWarnings(run([0, 0, 5, 0, 0, 0], false).slice(0, 8), null, HEAD_THERMAL)).toEqual([]);
  });
});
