// Trapezoidal move times and the per-stop time model (protocol/planner.md "Time model"), in integer µs.

import { roundDiv } from './dose';

export interface Machine {
  vmaxUmS: [number, number];
  accelUmS2: [number, number];
  settleUs: number;
  overheadUs: number;
  startUm: [number, number];
}

function isqrt(n: bigint): bigint {
  if (n < 2n) return n;
  let x = BigInt(Math.floor(Math.sqrt(Number(n))));
  while (x * x > n) x--;
  while ((x + 1n) * (x + 1n) <= n) x++;
  return x;
}

/** Time in µs to move `d` µm on one axis from rest to rest. */
export function moveTimeUs(d: number, v: number, a: number): number {
  if (d === 0) return 0;
  if (d * a >= v * v) return roundDiv(d * 1_000_000, v) + roundDiv(v * 1_000_000, a);
  return 2 * Number(isqrt((BigInt(d) * 1_000_000_000_000n) / BigInt(a)));
}

/** Caches move times by distance: plans repeat the same few distances millions of times. */
export class MoveTimes {
  readonly #cache = [new Map<number, number>(), new Map<number, number>()];
  constructor(private readonly machine: Machine) {}

  axis(axis: 0 | 1, d: number): number {
    const cache = this.#cache[axis];
    let t = cache.get(d);
    if (t === undefined) {
      t = moveTimeUs(d, this.machine.vmaxUmS[axis], this.machine.accelUmS2[axis]);
      cache.set(d, t);
    }
    return t;
  }

  /**
   * The time model's cost of one stop (protocol/planner.md "Time model"): the move from (fromX, fromY)
   * to (x, y) in µm, the settle after a move, the per-stop overhead, and its longest exposure.
   */
  stop(x: number, y: number, fromX: number, fromY: number, longestUs: number): number {
    const move = Math.max(this.axis(0, Math.abs(x - fromX)), this.axis(1, Math.abs(y - fromY)));
    return move + (move > 0 ? this.machine.settleUs : 0) + this.machine.overheadUs + longestUs;
  }
}
