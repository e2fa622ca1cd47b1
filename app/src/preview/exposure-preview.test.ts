import { describe, expect, it } from 'vitest';
import { headerOf } from '../planner/job-header';
import { planJob } from '../planner/planner-wasm';
import type { PrintJob } from '../protocol/job-types';
import { ledCoverage, previewGrid, timeline } from './exposure-preview';

const machine = { vmaxUmS: [100_000, 100_000] as [number, number], accelUmS2: [2_000_000, 1_500_000] as [number, number], settleUs: 2000, overheadUs: 1500, startUm: [0, 0] as [number, number], stepsMilli: [80_000, 80_000] as [number, number], linkBaud: 115200 };

function job(cols: number, rows: number, cell: (x: number, y: number) => number): PrintJob {
  return {
    grid: { cols, rows },
    pitchUm: { x: 50, y: 50 },
    originUm: { x: 10_000, y: 10_000 },
    dose: { map: 'linear', fullUs: 2550 },
    leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'serpentine' },
    gridData: Array.from({ length: rows }, (_, y) => Array.from({ length: cols }, (_, x) => cell(x, y))),
  };
}

describe('previewGrid', () => {
  const j = job(8, 8, (x, y) => (x === y ? 255 : x === 7 - y ? 51 : 0));
  const plan = planJob({ header: headerOf(j), cells: j.gridData }, machine);

  it('shows every cell with its dose and the LED that gave it, once every stop is in', () => {
    const g = previewGrid(j, plan, plan.count);
    expect([g.width, g.height, g.scale, g.maxUs]).toEqual([8, 8, 1, 2550]);
    for (let y = 0; y < 8; y++) {
      expect(g.doseUs[y * 8 + y]).toBe(2550);
      expect(g.doseUs[y * 8 + 7 - y]).toBe(510);
      expect(g.led[y * 8 + y]).toBe((y % 4) + 1); // rows 0-3 take LEDs 1-4, and so on
    }
    expect(g.doseUs.filter((v) => v > 0).length).toBe(16);
  });

  it('shows only the stops before the scrubber, at the whole job scale', () => {
    const none = previewGrid(j, plan, 0);
    expect(none.doseUs.every((v) => v === 0)).toBe(true);
    expect(none.maxUs).toBe(2550);
    const half = previewGrid(j, plan, Math.floor(plan.count / 2)).doseUs.filter((v) => v > 0).length;
    expect(half).toBeGreaterThan(0);
    expect(half).toBeLessThan(16);
  });

  it('bins a big job down to the preview size, keeping the brightest cell of each bin', () => {
    const big = job(1000, 10, (x) => (x === 999 ? 255 : x % 2 ? 10 : 0));
    const g = previewGrid(big, planJob({ header: headerOf(big), cells: big.gridData }, machine), Infinity, 100);
    expect([g.width, g.height, g.scale]).toEqual([100, 1, 10]);
    expect(g.doseUs[99]).toBe(2550);
    expect(g.doseUs[0]).toBe(100);
  });
});

describe('timeline and ledCoverage', () => {
  it('ends at the planner estimate, rising at every stop', () => {
    const j = job(16, 8, (x, y) => ((x + y) % 3 ? 128 : 0));
    const plan = planJob({ header: headerOf(j), cells: j.gridData }, machine);
    const t = timeline(j, plan, machine);
    expect(t.at(-1)).toBe(plan.estimateUs);
    for (let i = 1; i < t.length; i++) expect(t[i]).toBeGreaterThan(t[i - 1]);
    expect(ledCoverage(plan).reduce((a, b) => a + b, 0)).toBe(j.gridData.flatMap((r) => Array.from(r)).filter((v) => v > 0).length);
  });
});
