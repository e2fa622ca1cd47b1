// The app's tests' jobs and machines: random small jobs over several geometries, and a job's stop plan
// as the planner's vectors write it (protocol/vectors/planner-cpp.json).

import type { PrintJob, StrategyName } from '../protocol/job-types';
import { headerOf } from './job-header';
import type { MixedPlan, Plan } from './plan';
import { planJob } from './planner-wasm';
import type { MotionModel } from './time-model';

export const GEOMETRIES: Record<string, [number, number][]> = {
  adjacent: [[0, 0], [0, 1], [0, 2], [0, 3]],
  bands: [[0, 0], [0, 3], [0, 6], [0, 9]],
  coincident: [[0, 0], [0, 0], [0, 0], [0, 0]],
  mixed: [[0, 0], [2, 1], [-1, 1], [3, -2]],
};
export const STRATEGIES: StrategyName[] = ['raster', 'serpentine', 'shortest', 'random'];

export const MACHINE: MotionModel = {
  vmaxUmS: [150_000, 100_000],
  accelUmS2: [3_000_000, 2_000_000],
  settleUs: 2000,
  overheadUs: 1500,
  startUm: [0, 0],
  stepsMilli: [80_000, 80_000],
  linkBaud: 115200,
};

/** The same machine on a printhead link raised to 250000 baud (nano.md "Link speed"), as the board runs it. */
export const RAISED_MACHINE: MotionModel = { ...MACHINE, linkBaud: 250000 };

function rng(seed: number) {
  let x = Math.imul(seed, 0x9e3779b1) >>> 0 || 1;  // spread small consecutive seeds
  const next = () => {
    x ^= x << 13;
    x >>>= 0;
    x ^= x >>> 17;
    x ^= x << 5;
    x >>>= 0;
    return x / 4294967296;
  };
  for (let i = 0; i < 8; i++) next();
  return next;
}

/** A random job: a few blobs and dots of random values on a small grid. */
export function randomJob(seed: number, geometry: [number, number][], strategy: StrategyName, size?: [number, number], density?: number): PrintJob {
  const r = rng(seed);
  const cols = size?.[0] ?? 4 + Math.floor(r() * 14), rows = size?.[1] ?? 4 + Math.floor(r() * 12);
  const cells = Array.from({ length: rows }, () => new Array<number>(cols).fill(0));
  const fill = density ?? 0.2 + r() * 0.6;
  for (let y = 0; y < rows; y++) for (let x = 0; x < cols; x++) if (r() < fill) cells[y][x] = 1 + Math.floor(r() * 255);
  const doses: PrintJob['dose'][] = [
    { map: 'threshold', level: 1 + Math.floor(r() * 128), fullUs: 1 + Math.floor(r() * 50000) },
    { map: 'linear', fullUs: 1 + Math.floor(r() * 50000) },
    { map: 'linear', targetUJcm2: 1000 + Math.floor(r() * 200000), irradianceUWcm2: [0, 0, 0, 0].map(() => 1000 + Math.floor(r() * 100000)) },
  ];
  return {
    grid: { cols, rows },
    pitchUm: { x: 50 + Math.floor(r() * 150), y: 50 + Math.floor(r() * 150) },
    originUm: { x: Math.floor(r() * 20000), y: Math.floor(r() * 20000) },
    dose: doses[Math.floor(r() * doses.length)],
    leds: { offsets: geometry, gainPermille: [0, 0, 0, 0].map(() => 800 + Math.floor(r() * 400)) },
    strategy: { name: strategy, seed: Math.floor(r() * 4294967296) },
    gridData: cells,
  };
}

export interface GoldenCase {
  name: string;
  job: PrintJob;
  machine: MotionModel;
  plan: { stops: number[][]; passes: number; estimateUs: number; travelUm: [number, number] };
}

/** A plan's stops as the golden vectors write them: `[hx, hy, µs LED 0, 1, 2, 3]`. */
export function planStops(p: Plan): number[][] {
  return Array.from({ length: p.count }, (_, i) => [p.hx[i], p.hy[i], ...p.durations.subarray(i * 4, i * 4 + 4)]);
}

export function planCase(name: string, job: PrintJob, machine: MotionModel): GoldenCase {
  const p = planJob({ header: headerOf(job), cells: job.gridData }, machine);
  return { name, job, machine, plan: { stops: planStops(p), passes: p.passes, estimateUs: p.estimateUs, travelUm: p.travelUm } };
}

/** A mixed plan as the firmware's vectors write it (protocol/vectors/mixed-cpp.json). */
export function mixedVector(plan: MixedPlan): object {
  const passes = plan.passes.map((p) => {
    const base = { hy: p.hy, descending: p.descending, first: p.first, last: p.last, scanUs: p.scanUs, stopsUs: p.stopsUs, scan: p.scan };
    if (!p.scan) return { ...base, ...(p.band ? { band: p.band } : {}), stops: p.stops };
    const s = p.pass;
    return { ...base, windowUs: s.windowUs, jumps: s.jumps, events: s.events, moveUs: s.moveUs, startSteps: s.startSteps, stopSteps: s.stopSteps, strokeUs: s.strokeUs, markUs: s.markUs };
  });
  return { windowUs: plan.windowUs, passes, steps: plan.steps, estimateUs: plan.estimateUs };
}
