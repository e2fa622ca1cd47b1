// The C++ planners as WebAssembly (planner-wasm.ts) plan every order exactly as the TypeScript planner
// does, on a grid of jobs, LED geometries and machines, and reproduce the golden vectors of both.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { boardMask, fillMask, pcbMask, photoMask, sparseMask, textMask, type Mask } from '../../../bench/masks';
import type { JobHeader, PrintJob, StrategyName } from '../protocol/job-types';
import { GEOMETRIES, MACHINE, planStops, randomJob, type GoldenCase } from './golden';
import { headerOf } from './job-header';
import { mixedAsPlan, scanAsPlan, strokeOnBed } from './job-plan';
import { mixedVector, planMixed } from './mixed';
import { planJob, type PlannerJob } from './planner';
import * as wasm from './planner-wasm';
import { planScan } from './scan';
import { engineMoveUs, moveTimeUs, type MotionModel } from './time-model';
import { loadNodePlannerWasm } from './wasm/node-planner-wasm';

loadNodePlannerWasm();

const ORDERS: StrategyName[] = ['raster', 'serpentine', 'shortest', 'random', 'scan', 'mixed'];

/** The orders as job-plan.ts weighs them, in the order it prefers them on a tie. */
const WEIGHED: StrategyName[] = ['scan', 'mixed', 'serpentine', 'shortest', 'raster', 'random'];

/** job-plan.ts planAnyJob as it was with the TypeScript planner. */
function tsPlanAnyJob(job: PlannerJob, machine: MotionModel) {
  const h = job.header;
  if (h.strategy === 'mixed') {
    const mixed = planMixed(job, machine);
    return { plan: mixedAsPlan(mixed, machine, h), scan: null, mixed };
  }
  if (h.strategy !== 'scan') return { plan: planJob(job, machine), scan: null, mixed: null };
  const scan = planScan(job, machine);
  return { plan: scanAsPlan(scan, machine, h), scan, mixed: null };
}

/**
 * The TypeScript planner's weighing of the six orders, the rule the app used before it planned with
 * the module (job-plan.ts): each order planned, an order that cannot plan a job that has light
 * (a scan pass over the 32-bit limit) Infinity, and a scan or mixed plan whose strokes leave the bed.
 */
function orderEstimates(job: PlannerJob, machine: MotionModel, bedXUm = Infinity): Record<StrategyName, number> {
  const out = {} as Record<StrategyName, number>;
  let lit = false;
  // A scan's strokes run up and out beyond the artwork: one that leaves the bed is no choice.
  for (const name of WEIGHED) {
    const { plan, scan, mixed } = tsPlanAnyJob({ ...job, header: { ...job.header, strategy: name } }, machine);
    const strokes = scan?.passes ?? mixed?.passes.flatMap((p) => (p.scan ? [p.pass] : [])) ?? [];
    const offBed = strokes.some((p) => !strokeOnBed(p, machine, bedXUm));
    out[name] = offBed ? Infinity : plan.count || !lit ? plan.estimateUs : Infinity;
    if (name !== 'scan' && name !== 'mixed' && plan.count) lit = true;
  }
  // A scan or mixed plan that is empty where stops are not: refused (planner.md "Limits").
  if (lit && out.scan === 0) out.scan = Infinity;
  if (lit && out.mixed === 0) out.mixed = Infinity;
  return out;
}


/** The bench's two heads (bench/planner.bench.ts GEOMETRY), a head of four LEDs on one cell, and a staggered one. */
const HEADS: Record<string, [number, number][]> = {
  'adjacent rows': [[0, 0], [0, 1], [0, 2], [0, 3]],
  'bands 1/4 apart': [[0, 0], [0, 100], [0, 200], [0, 300]],
  coincident: GEOMETRIES.coincident,
  staggered: [[0, 0], [1, 2], [-2, 5], [0, -1]],
};

/** The golden vectors' machine, the bench's on the raised link, and a slow one that caps the scan's speed. */
const MACHINES: Record<string, MotionModel> = {
  golden: MACHINE,
  bench: { vmaxUmS: [100_000, 100_000], accelUmS2: [2_000_000, 1_500_000], settleUs: 2000, overheadUs: 4300, startUm: [0, 0], stepsMilli: [80_000, 80_000], linkBaud: 250000 },
  slow: { vmaxUmS: [8000, 90000], accelUmS2: [600_000, 1_500_000], settleUs: 1000, overheadUs: 900, startUm: [0, 4000], stepsMilli: [80_000, 100_000], linkBaud: 115200 },
};

interface Case {
  name: string;
  cells: ArrayLike<number>[];
  dose: Pick<JobHeader, 'map' | 'level' | 'fullUs' | 'targetUJcm2' | 'irradianceUWcm2'>;
  pitchUm?: [number, number];
  knownRows?: number;
}

const threshold = (fullUs: number) => ({ map: 'threshold' as const, level: 128, fullUs });
const linear = (fullUs: number) => ({ map: 'linear' as const, level: 0, fullUs });
const mask = (m: Mask, dose: Case['dose']): Case => ({ name: `${m.name} ${m.cols}×${m.rows}`, cells: m.cells, dose });
const blank = (cols: number, rows: number) => Array.from({ length: rows }, () => new Uint8Array(cols));
const oneCell = blank(9, 7);
oneCell[3][4] = 200;
const random = randomJob(38_1, GEOMETRIES.adjacent, 'raster', [40, 24]);
const prefix = boardMask(48, 40);

/** A dozen jobs: the bench's masks at small sizes, random cells, doses by target, and the edges. */
const JOBS: Case[] = [
  mask(boardMask(64, 48), threshold(2000)),
  mask(sparseMask(80, 40), threshold(2000)),
  mask(fillMask(24, 20), threshold(2000)),
  mask(photoMask(48, 24), linear(2000)),
  mask(textMask(64, 40), threshold(2000)),
  mask(pcbMask(50, 40), threshold(1500)),
  { name: 'random cells, linear', cells: random.gridData, dose: linear(3100) },
  { name: 'random cells, by target', cells: random.gridData, dose: { map: 'linear', level: 0, targetUJcm2: 2500, irradianceUWcm2: [9000, 12000, 7000, 30000] } },
  { name: 'a photo whose programs outrun the link', cells: photoMask(70, 8).cells, dose: linear(1200), pitchUm: [60, 50] },
  { name: 'empty job', cells: blank(12, 10), dose: threshold(2000) },
  { name: 'one cell', cells: oneCell, dose: threshold(2000) },
  { name: 'a window too long for the step engine', cells: textMask(40, 30).cells, dose: threshold(200_000) },
  { name: 'a window too short for the step engine', cells: textMask(40, 30).cells, dose: threshold(100), pitchUm: [400, 50] },
  { name: 'switch times past 32 bits', cells: [new Uint8Array(3000).fill(255), new Uint8Array(3000)], dose: threshold(2_000_000) },
  { name: 'rows still to come', cells: prefix.cells.map((r, y) => (y < 25 ? r : new Uint8Array(r.length))), dose: threshold(2000), knownRows: 25 },
];

function job(c: Case, offsets: [number, number][], strategy: StrategyName): PlannerJob {
  const header: JobHeader = {
    cols: c.cells[0].length, rows: c.cells.length, pitchUm: c.pitchUm ?? [50, 50], originUm: [10000, 10000], ...c.dose,
    gainPermille: [1000, 950, 1040, 1000], thermal: [0, 250], offsets, strategy, seed: strategy === 'random' ? 7 : 0,
  };
  return { header, cells: c.cells, ...(c.knownRows !== undefined ? { knownRows: c.knownRows } : {}) };
}

/** What the grid's TypeScript plans came to: each must be met somewhere, or the grid misses a case. */
const reached = new Set<string>();

function bothPlans(j: PlannerJob, m: MotionModel): [unknown, unknown] {
  const s = j.header.strategy;
  if (s === 'scan') {
    const ts = planScan(j, m);
    if (ts.refused) reached.add('a scan refused');
    if (ts.windowUs && !ts.passes.length && !ts.refused) reached.add('a scan with light and no passes');
    if (ts.passes.some((p) => p.windowUs > ts.windowUs)) reached.add('a pass slowed for the link');
    if (ts.passes.some((p) => p.jumps.length)) reached.add('a blank stretch flown');
    return [wasm.planScan(j, m), ts];
  }
  if (s === 'mixed') {
    const ts = planMixed(j, m);
    if (ts.refused) reached.add('a mixed plan refused');
    for (const p of ts.passes) reached.add(p.scan ? 'a mixed pass on the move' : p.band ? 'a band of stops' : 'a mixed pass of stops');
    return [wasm.planMixed(j, m), ts];
  }
  const ts = planJob(j, m);
  if (j.knownRows !== undefined && ts.count) reached.add('a stream\'s prefix planned');
  return [wasm.planJob(j, m), ts];
}

describe('the planner module plans as the TypeScript planner', () => {
  for (const order of ORDERS) {
    for (const [head, offsets] of Object.entries(HEADS)) {
      it(`${order}, ${head}: every job on every machine`, () => {
        for (const [machine, m] of Object.entries(MACHINES)) {
          for (const c of JOBS) {
            const [fromWasm, fromTs] = bothPlans(job(c, offsets, order), m);
            expect(fromWasm, `${order} ${head} ${machine} ${c.name}`).toEqual(fromTs);
          }
        }
      });
    }
  }

  it('the grid reaches every kind of plan', () => {
    expect([...reached].sort()).toEqual([
      'a band of stops', 'a blank stretch flown', 'a mixed pass of stops', 'a mixed pass on the move', 'a mixed plan refused',
      'a pass slowed for the link', 'a scan refused', 'a scan with light and no passes', "a stream's prefix planned",
    ]);
  });

  it('weighs the six orders of each job as job-plan.ts does, on and off a bed', () => {
    for (const [head, offsets] of Object.entries(HEADS)) {
      for (const [machine, m] of Object.entries(MACHINES)) {
        for (const c of JOBS.filter((c) => c.knownRows === undefined)) {
          const j = job(c, offsets, 'serpentine');
          for (const bedXUm of [Infinity, 12_500]) expect(wasm.orderEstimates(j, m, bedXUm), `${head} ${machine} ${c.name} bed ${bedXUm}`).toEqual(orderEstimates(j, m, bedXUm));
        }
      }
    }
  });

  it('times a move as the time model does', () => {
    for (const m of Object.values(MACHINES)) {
      for (const d of [0, 1, 49, 50, 1000, 12_345, 250_000, 1_999_999]) {
        expect(wasm.moveTimeUs(d, m.vmaxUmS[0], m.accelUmS2[0])).toBe(moveTimeUs(d, m.vmaxUmS[0], m.accelUmS2[0]));
        expect(wasm.engineMoveUs(m, d % 4099, d % 777)).toBe(engineMoveUs(m, d % 4099, d % 777));
      }
    }
  });

  // The one known difference, between the planners themselves: the TypeScript planner refuses a job's
  // window before it looks for a pass; the C++ planner (the Mega's, M29) refuses a pass it cannot run,
  // so a job with nothing to expose plans empty there, and is not refused.
  it('plans an empty job at a window the step engine cannot run empty, unrefused, as the Mega does', () => {
    const j = job({ ...JOBS[0], cells: blank(12, 10), dose: threshold(200_000) }, HEADS['adjacent rows'], 'scan');
    const ts = planScan(j, MACHINE);
    expect(ts.refused).toMatch(/step engine/);
    expect(wasm.planScan(j, MACHINE)).toEqual({ ...ts, refused: undefined });
    expect(wasm.planMixed(j, MACHINE)).toEqual({ ...planMixed(j, MACHINE), refused: undefined });
  });

  it('refuses a printhead link speed the Nano does not have, as the TypeScript planner does', () => {
    const j = job(JOBS[0], HEADS['adjacent rows'], 'serpentine');
    expect(() => wasm.planJob(j, { ...MACHINE, linkBaud: 9600 })).toThrow(RangeError);
    expect(() => planJob(j, { ...MACHINE, linkBaud: 9600 })).toThrow(RangeError);
  });
});

describe('the planner module reproduces the golden vectors', () => {
  const dir = process.env.UV_VECTORS_DIR ? `file://${process.env.UV_VECTORS_DIR}/` : new URL('../../../protocol/vectors/', import.meta.url);
  const load = <T>(file: string): (T & { name: string; job: PrintJob; machine: MotionModel })[] => JSON.parse(readFileSync(new URL(file, dir), 'utf8')).cases;
  const plannerJob = (j: PrintJob): PlannerJob => ({ header: headerOf(j), cells: j.gridData });

  for (const by of ['cpp', 'ts']) {
    it(`planner-${by}.json`, () => {
      const cases = load<GoldenCase>(`planner-${by}.json`);
      expect(cases.length).toBeGreaterThan(20);
      for (const c of cases) {
        const p = wasm.planJob(plannerJob(c.job), c.machine);
        expect({ stops: planStops(p), passes: p.passes, estimateUs: p.estimateUs, travelUm: p.travelUm }, c.name).toEqual(c.plan);
      }
    });
    it(`scan-${by}.json`, () => {
      const cases = load<{ scan: unknown }>(`scan-${by}.json`);
      expect(cases.length).toBeGreaterThan(10);
      for (const c of cases) expect(wasm.planScan(plannerJob(c.job), c.machine), c.name).toEqual(c.scan);
    });
    it(`mixed-${by}.json`, () => {
      const cases = load<{ mixed: unknown }>(`mixed-${by}.json`);
      expect(cases.length).toBeGreaterThanOrEqual(10);
      for (const c of cases) expect(mixedVector(wasm.planMixed(plannerJob(c.job), c.machine)), c.name).toEqual(c.mixed);
    });
  }
});
