// Test-only: a `cols` × `rows` block at 50 µm whose cells are lit with probability `fill` at a full
// dose of `fullMs`, from a seeded generator; a gray block mixes full and half cells.
import type { PrintJob, StrategyName } from '../protocol/job-types';

export function blockJob(fullMs: number, fill: number, cols: number, rows: number, o: { seed: number; strategy: StrategyName; gray: boolean }): PrintJob {
  let seed = o.seed;
  const rand = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32);
  const lit = () => (o.gray && rand() >= 0.5 ? 128 : 255);
  return {
    grid: { cols, rows },
    pitchUm: { x: 50, y: 50 },
    originUm: { x: 20_000, y: 20_000 },
    dose: { map: 'linear', fullUs: fullMs * 1000 },
    leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: o.strategy },
    gridData: Array.from({ length: rows }, () => Array.from({ length: cols }, () => (rand() < fill ? lit() : 0))),
  };
}
