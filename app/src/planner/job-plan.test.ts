import { describe, expect, it } from 'vitest';
import { fastestOrder, ORDERS, orderEstimates, passDurationUs, passSwitches, planAnyJob, strokeOnBed, strokeSpanUm } from './job-plan';
import { planJob, planScan } from './planner-wasm';
import { GEOMETRIES, randomJob } from './test-jobs';
import { CONFIG_DEFAULTS, motionOf } from '../machine/config';
import type { ScanPass, ScanPlan } from './plan';
import { headerOf } from './job-header';
import type { MotionModel } from './time-model';
import type { StrategyName } from '../protocol/job-types';

const MACHINE: MotionModel = { vmaxUmS: [100_000, 100_000], accelUmS2: [2_000_000, 2_000_000], settleUs: 2000, overheadUs: 1500, startUm: [0, 0], stepsMilli: [80_000, 80_000], linkBaud: 115200 };

const header = (cols: number, rows: number, name: StrategyName) => headerOf({
  grid: { cols, rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 5000, y: 5000 }, dose: { map: 'linear', fullUs: 4000 },
  leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] }, strategy: { name }, gridData: [],
});

const pass = (leds: [number, number][][]): ScanPass =>
  ({ hy: 0, descending: false, first: 0, last: 9, windowUs: 100, accelUs: 7, overscanUm: 1, runUpUm: 0, runOutUm: 0, leds, jumps: [], events: [], moveUs: 0, startSteps: 0, stopSteps: 0, strokeUs: 1234, markUs: 56, wallUs: 6634, chainBytes: 0, chainAheadBytes: 0 });

describe('a scan pass as the machine runs it', () => {
  it('switches the LEDs in time order, one mask per instant, each LED lit over its intervals', () => {
    // Gray and full cells under four LEDs a row apart: LEDs overlap, and one goes off where another comes on.
    const cells = Array.from({ length: 8 }, (_, y) => Array.from({ length: 24 }, (_, x) => ((x + 3 * y) % 5 === 0 ? 0 : (x * 40 + y * 17) % 256)));
    const { passes } = planScan({ header: header(24, 8, 'scan'), cells }, MACHINE);
    expect(passes.length).toBeGreaterThan(0);
    for (const p of passes) {
      const switches = passSwitches(p);
      const on: number[] = [0, 0, 0, 0];
      const lit: [number, number][][] = [[], [], [], []];
      let mask = 0, at = -1;
      for (const s of switches) {
        expect(s.atUs).toBeGreaterThan(at);
        expect(s.mask).not.toBe(mask);
        for (let k = 0; k < 4; k++) {
          if (!((mask >> k) & 1) && (s.mask >> k) & 1) on[k] = s.atUs;
          if ((mask >> k) & 1 && !((s.mask >> k) & 1)) lit[k].push([on[k], s.atUs]);
        }
        [mask, at] = [s.mask, s.atUs];
      }
      expect(mask).toBe(0);
      expect(lit).toEqual(p.leds);
    }
  });

  it('lasts its stroke, as the step engine runs it', () => {
    const scan = { windowUs: 100, accelUs: 7 } as ScanPlan;
    expect(passDurationUs(scan, pass([]))).toBe(1234);
  });
});

describe('planning by strategy', () => {
  it('plans stops for the stop-and-fire strategies and passes, counted as stops, for scan', () => {
    const cells = [[255, 0, 0, 255, 128, 0], [0, 0, 0, 0, 0, 0], [64, 64, 0, 0, 0, 0]];
    const stops = planAnyJob({ header: header(6, 3, 'serpentine'), cells }, MACHINE);
    expect(stops.scan).toBeNull();
    expect(stops.plan).toEqual(planJob({ header: header(6, 3, 'serpentine'), cells }, MACHINE));
    const scan = planAnyJob({ header: header(6, 3, 'scan'), cells }, MACHINE);
    expect(scan.scan?.passes.length).toBeGreaterThan(0);
    expect(scan.plan.count).toBe(scan.scan!.passes.length);
    expect(scan.plan.estimateUs).toBe(scan.scan!.estimateUs);
    expect(Array.from(scan.plan.hy)).toEqual(scan.scan!.passes.map((p) => p.hy));
  });
});

describe('a mixed plan as the Mega counts it', () => {
  it('counts each pass on the move once and each stop once, with the stops\' durations and the mixed estimate', () => {
    // Dense bands of four rows between bands with one dot: passes on the move and passes of stops.
    const cells = Array.from({ length: 32 }, (_, y) => Array.from({ length: 80 }, (_, x) => ((y >> 2) % 2 === 0 ? 255 : y % 4 === 1 && x === (y * 37) % 80 ? 255 : 0)));
    const { plan, mixed, scan } = planAnyJob({ header: header(80, 32, 'mixed'), cells }, MACHINE);
    expect(scan).toBeNull();
    const ways = mixed!.passes.map((p) => p.scan);
    expect(ways).toContain(true);
    expect(ways).toContain(false);
    expect(plan.count).toBe(mixed!.steps);
    expect(plan.count).toBe(mixed!.passes.reduce((n, p) => n + (p.scan ? 1 : p.stops.length), 0));
    expect(plan.estimateUs).toBe(mixed!.estimateUs);
    expect(plan.passes).toBe(mixed!.passes.length);
    const stops = mixed!.passes.flatMap((p) => (p.scan ? [[p.pass.descending ? p.pass.last : p.pass.first, p.hy, 0, 0, 0, 0]] : p.stops));
    expect(Array.from({ length: plan.count }, (_, i) => [plan.hx[i], plan.hy[i], ...plan.durations.subarray(4 * i, 4 * i + 4)])).toEqual(stops);
    // Never slower than either pure mode here, and the automatic order takes it.
    const est = orderEstimates({ header: header(80, 32, 'mixed'), cells }, MACHINE);
    expect(est.mixed).toBeLessThan(est.scan);
    expect(est.mixed).toBeLessThan(Math.min(est.serpentine, est.shortest, est.raster, est.random));
    expect(fastestOrder(est)).toBe('mixed');
  });
});

describe('the automatic order', () => {
  const job = (cols: number, rows: number, lit: (x: number, y: number) => boolean, fullUs: number) => ({
    header: { ...header(cols, rows, 'serpentine'), fullUs, map: 'threshold' as const, level: 128 },
    cells: Array.from({ length: rows }, (_, y) => Array.from({ length: cols }, (_, x) => (lit(x, y) ? 255 : 0))),
  });

  it('gives every order its estimate, the one its plan counts, and picks the fastest', () => {
    const j = job(60, 24, (x, y) => (x * 7 + y * 3) % 5 !== 0, 4000);
    const est = orderEstimates(j, MACHINE);
    for (const name of ORDERS) expect(est[name]).toBe(planAnyJob({ ...j, header: { ...j.header, strategy: name } }, MACHINE).plan.estimateUs);
    expect(fastestOrder(est)).toBe('scan');
    expect(est.scan).toBeLessThan(est.serpentine / 3);
  });

  it('takes stops for a few dots far apart, where a pass on the move crosses the whole bed for each', () => {
    const j = job(400, 40, (x, y) => (x === 3 || x === 396) && y % 9 === 0, 2000);
    const est = orderEstimates(j, MACHINE);
    expect(est.scan).toBeGreaterThan(Math.min(est.serpentine, est.shortest));
    // Mixed takes them as a band of stops, as `shortest` does (planner.md "Bands"), and wins the tie.
    expect(est.mixed).toBeLessThanOrEqual(Math.min(est.serpentine, est.shortest));
    expect(['mixed', 'serpentine', 'shortest']).toContain(fastestOrder(est));
    expect(fastestOrder(est)).not.toBe('scan');
  });

  it('never picks a scan the step engine cannot run (mega.md M29: a step over 32.768 ms, or over 16000 steps/s)', () => {
    // 200 ms windows at 50 µm, 80 steps/mm: 50 ms a step. Dense and long-dosed, where a scan would otherwise win.
    const j = job(60, 24, () => true, 200_000);
    const est = orderEstimates(j, MACHINE);
    expect(est.scan).toBe(Infinity);
    expect(fastestOrder(est)).not.toBe('scan');
    // The same job at 130 ms a cell (32.5 ms a step) runs, and the scan is the fastest.
    expect(fastestOrder(orderEstimates(job(60, 24, () => true, 130_000), MACHINE))).toBe('scan');
  });

  it('prefers scan on a tie, and never an order that cannot plan a job with light', () => {
    expect(fastestOrder({ scan: 5, mixed: 5, serpentine: 5, shortest: 5, raster: 5, random: 5 })).toBe('scan');
    expect(fastestOrder({ scan: Infinity, mixed: Infinity, serpentine: 9, shortest: 7, raster: 8, random: 9 })).toBe('shortest');
  });
});

describe('the automatic order on a bed', () => {
  it('never picks a scan whose strokes would leave the bed', () => {
    const job = randomJob(5, GEOMETRIES.adjacent, 'scan', [200, 20], 1);
    job.originUm = { x: 190_000, y: 20_000 }; // its right edge at the bed's: the run-out is beyond it
    job.pitchUm = { x: 50, y: 50 };
    job.dose = { map: 'linear', fullUs: 2000 };
    const p = { header: headerOf(job), cells: job.gridData };
    const machine = motionOf(CONFIG_DEFAULTS, [0, 0]);
    expect(Number.isFinite(orderEstimates(p, machine).scan)).toBe(true);
    const onBed = orderEstimates(p, machine, 200_000);
    expect(onBed.scan).toBe(Infinity);
    expect(fastestOrder(onBed)).not.toBe('scan');
  });
});

describe("a stroke's place on the bed", () => {
  const m = { ...MACHINE, stepsMilli: [80_201, 80_201] as [number, number] }; // 80.201 steps/mm
  const rightwards = { ...pass([[], [], [], []]), startSteps: 100, stopSteps: 15_960 };

  it('runs from the lower step to the higher, whichever way the pass goes', () => {
    for (const p of [rightwards, { ...rightwards, startSteps: 15_960, stopSteps: 100 }]) {
      expect(strokeSpanUm(p, m)).toEqual({ minUm: (100 * 1e6) / 80_201, maxUm: (15_960 * 1e6) / 80_201 });
    }
  });

  it('is on the bed exactly when the Mega says so: in whole steps, the bed rounded to the nearest', () => {
    // A 199 mm bed is 15959.999 steps, which the Mega rounds to 15960 (Motion::onBed).
    expect(strokeOnBed(rightwards, m, 199_000)).toBe(true);
    expect(strokeOnBed({ ...rightwards, stopSteps: 15_961 }, m, 199_000)).toBe(false);
    expect(strokeOnBed({ ...rightwards, startSteps: 15_961, stopSteps: 100 }, m, 199_000)).toBe(false);
    expect(strokeOnBed({ ...rightwards, startSteps: -1 }, m, 199_000)).toBe(false);
    expect(strokeOnBed({ ...rightwards, startSteps: 0 }, m, Infinity)).toBe(true);
  });
});

describe('the printhead link speed a plan is made for', () => {
  const job = randomJob(7, GEOMETRIES.adjacent, 'serpentine');
  const cells = { header: headerOf(job), cells: job.gridData };
  it('is refused when the link has no such speed, never rounded', () => {
    for (const strategy of ['serpentine', 'scan', 'mixed'] as StrategyName[]) {
      expect(() => planAnyJob({ ...cells, header: { ...cells.header, strategy } }, { ...MACHINE, linkBaud: 230400 })).toThrow(/no speed 230400 baud/);
    }
  });
  it('shortens each stop by its F line at the raised speed', () => {
    const slow = planJob(cells, MACHINE), fast = planJob(cells, { ...MACHINE, linkBaud: 250000 });
    expect(fast.count).toBe(slow.count);
    expect(fast.estimateUs).toBeLessThan(slow.estimateUs);
  });
});
