// P2: planned exposure time per mask against a lower bound and against unidirectional raster.
// P7: planning plus preview data for 1 M cells, against a plain pass over the cells, by the app's planner
// (the C++ planner as WebAssembly, app/src/planner/planner-wasm.ts).
import type { JobHeader, StrategyName } from '../app/src/protocol/job-types';
import type { Plan } from '../app/src/planner/plan';
import { moveTimeUs, planJob } from '../app/src/planner/planner-wasm';
import type { MotionModel } from '../app/src/planner/time-model';
import { durationTables } from '../app/src/planner/dose';
import { compare, type Row } from './harness';
import { BOARD_LINK_BAUD } from '../app/src/machine/config';
import { boardMask, fillMask, photoMask, sparseMask, textMask, type Mask } from './masks';

export const BENCH_MACHINE: MotionModel = {
  vmaxUmS: [100_000, 100_000],
  accelUmS2: [2_000_000, 1_500_000],
  settleUs: 2000,
  overheadUs: 4300, // stop_overhead_us: what the real images spend a stop beyond move, settle, F line and light (StopCycle)
  startUm: [0, 0],
  stepsMilli: [80_000, 80_000],
  linkBaud: BOARD_LINK_BAUD, // the speed the board runs jobs at (printhead_link.h)
};

export const GEOMETRY: Record<string, [number, number][]> = {
  'adjacent rows': [[0, 0], [0, 1], [0, 2], [0, 3]],
  'bands 1/4 apart': [[0, 0], [0, 100], [0, 200], [0, 300]],
};

function header(mask: Mask, offsets: [number, number][], strategy: StrategyName, map: 'linear' | 'threshold'): JobHeader {
  return {
    cols: mask.cols, rows: mask.rows, pitchUm: [50, 50], originUm: [10000, 10000], map, level: 128, fullUs: 2000,
    gainPermille: [1000, 1000, 1000, 1000], thermal: [0, 250], offsets, strategy, seed: 7,
  };
}

/**
 * No plan can beat this: every lit cell's exposure shared perfectly by four LEDs, the fewest
 * stops that can hold the cells (each with its overhead and settle), and one cell pitch of
 * travel between consecutive stops.
 */
export function lowerBoundUs(h: JobHeader, mask: Mask, m: MotionModel): number {
  const tables = durationTables(h);
  let sum = 0, lit = 0;
  for (const row of mask.cells) for (let c = 0; c < row.length; c++) if (tables[0][row[c]] > 0) (sum += tables[0][row[c]]), lit++;
  const stops = Math.ceil(lit / 4);
  const step = Math.min(moveTimeUs(h.pitchUm[0], m.vmaxUmS[0], m.accelUmS2[0]), moveTimeUs(h.pitchUm[1], m.vmaxUmS[1], m.accelUmS2[1]));
  return sum / 4 + stops * (m.overheadUs + m.settleUs) + Math.max(0, stops - 1) * step;
}

export interface P2Row {
  mask: string;
  geometry: string;
  strategy: StrategyName;
  plan: Plan;
  bound: number;
  raster: number;
}

export function p2(): P2Row[] {
  const masks: [Mask, 'linear' | 'threshold'][] = [
    [boardMask(800, 400), 'threshold'],
    [sparseMask(800, 400), 'threshold'],
    [fillMask(200, 200), 'threshold'],
    [photoMask(300, 200), 'linear'],
    [textMask(800, 400), 'threshold'],
  ];
  const out: P2Row[] = [];
  for (const [mask, map] of masks) {
    for (const [geometry, offsets] of Object.entries(GEOMETRY)) {
      const cells = mask.cells;
      const raster = planJob({ header: header(mask, offsets, 'raster', map), cells }, BENCH_MACHINE).estimateUs;
      for (const strategy of ['serpentine', 'shortest'] as StrategyName[]) {
        const h = header(mask, offsets, strategy, map);
        out.push({ mask: mask.name, geometry, strategy, plan: planJob({ header: h, cells }, BENCH_MACHINE), bound: lowerBoundUs(h, mask, BENCH_MACHINE), raster });
      }
    }
  }
  return out;
}

export function printP2(rows: P2Row[]): void {
  console.log('\nP2 planned time vs lower bound (goal: pcb <= 1.10x) and vs unidirectional raster (goal: sparse >= 2x)');
  console.log('  mask    geometry          strategy     stops   planned     bound   /bound  raster speed-up');
  for (const r of rows) {
    const t = r.plan.estimateUs / 1e6;
    console.log(`  ${r.mask.padEnd(7)} ${r.geometry.padEnd(17)} ${r.strategy.padEnd(11)} ${String(r.plan.count).padStart(6)} ${t.toFixed(1).padStart(8)} s ${(r.bound / 1e6).toFixed(1).padStart(8)} s ${(r.plan.estimateUs / r.bound).toFixed(2).padStart(6)}x ${(r.raster / r.plan.estimateUs).toFixed(2).padStart(8)}x`);
  }
}

export function p7(): Row[] {
  const mask = boardMask(1024, 1024);
  const h = header(mask, GEOMETRY['adjacent rows'], 'shortest', 'threshold');
  let sink = 0;
  return compare('P7 planning + preview data, 1 M cells (the C++ planner as WebAssembly; goal <= 300 ms)', {
    name: 'baseline: one pass summing every cell', run: () => {
      for (const row of mask.cells) for (let i = 0; i < row.length; i++) sink += row[i];
    },
  }, [{
    name: 'plan + per-cell dose map for the preview', run: () => {
      const plan = planJob({ header: h, cells: mask.cells }, BENCH_MACHINE);
      const dose = new Uint32Array(mask.cols * mask.rows);
      for (let i = 0; i < plan.count; i++)
        for (let k = 0; k < 4; k++) {
          const us = plan.durations[i * 4 + k];
          if (us) dose[(plan.hy[i] + h.offsets[k][1]) * mask.cols + plan.hx[i] + h.offsets[k][0]] += us;
        }
      sink += dose[0];
    },
  }], 7);
}
