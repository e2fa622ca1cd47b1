// The app's planner, the C++ planners as WebAssembly (planner-wasm.ts): a grid of jobs, LED geometries
// and machines that reaches every kind of plan, the six orders weighed as each is planned, and the
// firmware's scan vectors decoded to the last word.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { boardMask, fillMask, pcbMask, photoMask, sparseMask, textMask, type Mask } from '../../../bench/masks';
import type { JobHeader, PrintJob, StrategyName } from '../protocol/job-types';
import { headerOf } from './job-header';
import { planAnyJob, strokeOnBed } from './job-plan';
import type { PlannerJob, ScanPlan } from './plan';
import * as wasm from './planner-wasm';
import { GEOMETRIES, MACHINE, randomJob } from './test-jobs';
import type { MotionModel } from './time-model';
import { loadNodePlannerWasm } from './wasm/node-planner-wasm';

loadNodePlannerWasm();

const ORDERS: StrategyName[] = ['raster', 'serpentine', 'shortest', 'random', 'scan', 'mixed'];

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

/** What the grid's plans came to: each must be met somewhere, or the grid misses a case. */
const reached = new Set<string>();

/** A plan of any order, with what it reached, and the estimate each pass adds up to. */
function planOf(j: PlannerJob, m: MotionModel): number {
  const s = j.header.strategy;
  if (s === 'scan') {
    const p = wasm.planScan(j, m);
    if (p.refused) reached.add('a scan refused');
    if (p.windowUs && !p.passes.length && !p.refused) reached.add('a scan with light and no passes');
    if (p.passes.some((q) => q.windowUs > p.windowUs)) reached.add('a pass slowed for the link');
    if (p.passes.some((q) => q.jumps.length)) reached.add('a blank stretch flown');
    expect(p.passes.reduce((t, q) => t + q.wallUs, 0), 'a scan plan is its passes').toBe(p.estimateUs);
    return p.estimateUs;
  }
  if (s === 'mixed') {
    const p = wasm.planMixed(j, m);
    if (p.refused) reached.add('a mixed plan refused');
    for (const q of p.passes) {
      reached.add(q.scan ? 'a mixed pass on the move' : q.band ? 'a band of stops' : 'a mixed pass of stops');
      if (q.scan) expect(q.pass.wallUs, 'a pass on the move costs its stroke').toBe(q.scanUs);
    }
    expect(p.passes.reduce((t, q) => t + (q.scan ? q.scanUs : q.stopsUs), 0), 'a mixed plan is its passes the way taken').toBe(p.estimateUs);
    return p.estimateUs;
  }
  const p = wasm.planJob(j, m);
  if (j.knownRows !== undefined && p.count) reached.add("a stream's prefix planned");
  return p.estimateUs;
}

describe('the planner module', () => {
  it('plans every order of every job on every head and machine, and the grid reaches every kind of plan', () => {
    for (const order of ORDERS) {
      for (const offsets of Object.values(HEADS)) {
        for (const m of Object.values(MACHINES)) for (const c of JOBS) planOf(job(c, offsets, order), m);
      }
    }
    expect([...reached].sort()).toEqual([
      'a band of stops', 'a blank stretch flown', 'a mixed pass of stops', 'a mixed pass on the move', 'a mixed plan refused',
      'a pass slowed for the link', 'a scan refused', 'a scan with light and no passes', "a stream's prefix planned",
    ]);
  });

  it('weighs each of the six orders at the estimate its own plan counts, Infinity where it cannot run, on and off a bed', () => {
    for (const [head, offsets] of Object.entries(HEADS)) {
      for (const [machine, m] of Object.entries(MACHINES)) {
        for (const c of JOBS.filter((c) => c.knownRows === undefined)) {
          const j = job(c, offsets, 'serpentine');
          for (const bedXUm of [Infinity, 12_500]) {
            const weighed = wasm.orderEstimates(j, m, bedXUm);
            for (const order of ORDERS) {
              const { plan, scan, mixed } = planAnyJob({ ...j, header: { ...j.header, strategy: order } }, m);
              const strokes = scan?.passes ?? mixed?.passes.flatMap((p) => (p.scan ? [p.pass] : [])) ?? [];
              const where = `${order} ${head} ${machine} ${c.name} bed ${bedXUm}`;
              if (Number.isFinite(weighed[order])) expect(weighed[order], where).toBe(plan.estimateUs);
              else expect(!plan.count || strokes.some((p) => !strokeOnBed(p, m, bedXUm)) || (plan.estimateUs === 0 && weighed.serpentine > 0), where).toBe(true);
            }
          }
        }
      }
    }
  });

  // The C++ planner (the Mega's, M29) refuses a pass it cannot run, so a job with nothing to expose
  // plans empty at a window the step engine cannot run, and is not refused.
  it('plans an empty job at a window the step engine cannot run empty, unrefused, as the Mega does', () => {
    const j = job({ ...JOBS[0], cells: blank(12, 10), dose: threshold(200_000) }, HEADS['adjacent rows'], 'scan');
    for (const p of [wasm.planScan(j, MACHINE), wasm.planMixed(j, MACHINE)]) expect([p.passes, p.estimateUs, p.refused]).toEqual([[], 0, undefined]);
  });

  it('refuses a printhead link speed the Nano does not have', () => {
    const j = job(JOBS[0], HEADS['adjacent rows'], 'serpentine');
    expect(() => wasm.planJob(j, { ...MACHINE, linkBaud: 9600 })).toThrow(RangeError);
  });

  it('prices a stop as the time model does: the move, the settle, the overhead, its F line and its longest exposure', () => {
    const m = MACHINES.golden;
    expect(wasm.stopCostUs(m, 0, 0, [0, 0, 0, 0])).toBe(m.overheadUs);
    // "F:1,500,0,0,0\n" is 14 bytes: 1215 µs at 115200 baud.
    expect(wasm.stopCostUs(m, 0, 0, [500, 0, 0, 0])).toBe(m.overheadUs + 1215 + 500);
    expect(wasm.stopCostUs(m, 80, 0, [500, 0, 0, 0])).toBe(wasm.engineMoveUs(m, 80, 0) + m.settleUs + m.overheadUs + 1215 + 500);
    expect([wasm.axisSteps(m, 0, 1006), wasm.axisSteps(m, 0, -1006), wasm.axisSteps(m, 1, 7)]).toEqual([80, -80, 1]);
  });
});

describe('the planner module reproduces the firmware\'s scan vectors', () => {
  const dir = process.env.UV_VECTORS_DIR ? `file://${process.env.UV_VECTORS_DIR}/` : new URL('../../../protocol/vectors/', import.meta.url);
  const cases: { name: string; job: PrintJob; machine: MotionModel; scan: ScanPlan }[] = JSON.parse(readFileSync(new URL('scan-cpp.json', dir), 'utf8')).cases;

  it('scan-cpp.json: every plan, each pass\'s time in the estimate its own', () => {
    expect(cases.length).toBeGreaterThan(10);
    for (const c of cases) {
      const p = wasm.planScan({ header: headerOf(c.job), cells: c.job.gridData }, c.machine);
      expect({ ...p, passes: p.passes.map(({ wallUs: _w, chainBytes: _c, chainAheadBytes: _a, ...rest }) => rest) }, c.name).toEqual(c.scan);
      expect(p.passes.reduce((t, q) => t + q.wallUs, 0), c.name).toBe(p.estimateUs);
      // The chain's bytes are the link check's (planner tests, ScanLink): here, that they come across.
      for (const q of p.passes) expect(q.events.length > 0 ? q.chainAheadBytes > 0 && q.chainAheadBytes <= q.chainBytes : q.chainBytes === 0, c.name).toBe(true);
    }
    console.log(`[vectors] scan-cpp.json: ${cases.length} scan plans checked (the C++ planner as WebAssembly)`);
  });
});
