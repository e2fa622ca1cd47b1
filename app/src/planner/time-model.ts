// Move times (the continuous trapezoid, and the Mega's step engine as it runs a move) and the
// per-stop time model (protocol/planner.md "Time model"), in integer µs.

import { NANO_LINK_BAUDS as LINK_BAUDS } from '../protocol/nano';
import { roundDiv } from './dose';

/**
 * µs the stop's `F:m,d0,d1,d2,d3` line takes on the printhead link at `baud`, ten bits a byte,
 * rounded down (protocol/planner.md "Time model"); 0 for a stop that lights nothing (no F goes).
 */
export function fireLineUs(us: ArrayLike<number>, baud: number): number {
  let mask = 0;
  let bytes = 7; // "F:", the four commas, the newline
  for (let k = 0; k < 4; k++) {
    if (us[k] > 0) mask |= 1 << k;
    bytes += String(us[k]).length;
  }
  return mask ? Math.floor(((bytes + String(mask).length) * 10_000_000) / baud) : 0;
}

export interface MotionModel {
  vmaxUmS: [number, number];
  accelUmS2: [number, number];
  settleUs: number;
  overheadUs: number;
  startUm: [number, number];
  /** X and Y steps per mm × 1000: the step engine moves in whole steps. */
  stepsMilli: [number, number];
  /**
   * The printhead link's speed the job runs at, one of the Nano's `L` speeds (nano.md "Link speed"):
   * it times each stop's F line, a pass's G lead and its programs on the wire (planner.md).
   */
  linkBaud: number;
}

/**
 * The Mega's step engine as the time model prices it (firmware/mega/src/step_profile.h): a 2 MHz
 * step timer, 32 to 16000 steps/s on the dominant axis, segments of about 2.5 ms (400 a second).
 */
export const ENGINE_TICK_HZ = 2_000_000;
export const ENGINE_MAX_RATE = 16000;
export const ENGINE_MIN_RATE = 32;
const ENGINE_SEGMENTS_PER_S = 400;

/** A move's profile on its dominant axis, in steps: its length, cruise rate, acceleration and ramp. */
export interface StepRamp {
  total: number;
  rate: number;
  accel: number;
  ramp: number;
}

/** From each axis's steps and limits (steps/s, steps/s²), scaled to the dominant axis as the Mega's profileFor does. */
export function stepRamp(steps: number[], rate: number[], accel: number[]): StepRamp {
  const total = Math.max(...steps);
  let r = ENGINE_MAX_RATE, a = 0xffffffff;
  steps.forEach((n, i) => {
    if (!n) return;
    r = Math.min(r, Math.floor((rate[i] * total) / n));
    a = Math.min(a, Math.floor((accel[i] * total) / n));
  });
  r = Math.max(r, ENGINE_MIN_RATE);
  a = Math.max(a, 1);
  return { total, rate: r, accel: a, ramp: Math.ceil((r * r) / (2 * a)) };
}

function isqrt32(n: number): number {
  let r = Math.floor(Math.sqrt(n));
  while (r * r > n) r--;
  while ((r + 1) * (r + 1) <= n) r++;
  return r;
}

function rateAt(p: StepRamp, d2: number): number {
  if (d2 >= 2 * p.ramp) return p.rate;
  return Math.max(Math.min(isqrt32(p.accel * d2), p.rate), ENGINE_MIN_RATE);
}

const segmentSteps = (rate: number, remaining: number) => Math.min(Math.max(Math.floor(rate / ENGINE_SEGMENTS_PER_S), 1), remaining, 0xffff);

/**
 * Timer ticks (0.5 µs) the engine takes for steps [from, to) of a move, segment by segment as Motion
 * cuts them (one that would run past `to` ends there at its rate), each step's interval counted, the
 * last one's too: the engine is idle only after it.
 */
export function stepTicks(p: StepRamp, from: number, to: number): number {
  let ticks = 0;
  for (let done = from; done < to; ) {
    const remaining = p.total - done;
    if (done >= p.ramp) {
      // At the cruise rate: whole segments that stay clear of the ramp down, counted at once.
      const k = segmentSteps(p.rate, Infinity);
      const need = Math.max(2 * p.ramp + k, 2 * k);
      if (2 * remaining >= need) {
        const n = Math.min(Math.floor((2 * remaining - need) / (2 * k)) + 1, Math.floor((to - done) / k));
        if (n > 0) {
          ticks += n * k * Math.floor(ENGINE_TICK_HZ / p.rate);
          done += n * k;
          continue;
        }
      }
    }
    let k = segmentSteps(rateAt(p, Math.min(2 * done + 1, 2 * remaining - 1)), remaining);
    const interval = Math.floor(ENGINE_TICK_HZ / rateAt(p, Math.min(2 * done + k, 2 * remaining - k)));
    k = Math.min(k, to - done);
    ticks += k * interval;
    done += k;
  }
  return ticks;
}

/** An axis's position in steps for `um` (Motion::toSteps: rounded half away from zero). */
export function axisSteps(m: MotionModel, axis: 0 | 1, um: number): number {
  const n = um * m.stepsMilli[axis];
  return Math.sign(n) * Math.floor((Math.abs(n) + 500_000) / 1_000_000);
}

/** The axis's top rate (steps/s) and acceleration (steps/s²), as the Mega's Motion::limits gives them. */
export const axisRate = (m: MotionModel, axis: 0 | 1) => Math.min(Math.floor((m.vmaxUmS[axis] * m.stepsMilli[axis]) / 1_000_000), ENGINE_MAX_RATE);
export const axisAccel = (m: MotionModel, axis: 0 | 1) => Math.floor((m.accelUmS2[axis] * m.stepsMilli[axis]) / 1_000_000);

/** The µs the step engine takes to move by (dx, dy) steps from rest to rest, until it is idle. */
export function engineMoveUs(m: MotionModel, dx: number, dy: number): number {
  if (!dx && !dy) return 0;
  const p = stepRamp([dx, dy], [axisRate(m, 0), axisRate(m, 1)], [axisAccel(m, 0), axisAccel(m, 1)]);
  return Math.floor((stepTicks(p, 0, p.total) + 1) / 2);
}

function isqrt(n: bigint): bigint {
  if (n < 2n) return n;
  let x = BigInt(Math.floor(Math.sqrt(Number(n))));
  while (x * x > n) x--;
  while ((x + 1n) * (x + 1n) <= n) x++;
  return x;
}

/** Time in µs to move `d` µm on one axis from rest to rest on the continuous trapezoid (a scan pass's flown stretch is planned on it). */
export function moveTimeUs(d: number, v: number, a: number): number {
  if (d === 0) return 0;
  if (d * a >= v * v) return roundDiv(d * 1_000_000, v) + roundDiv(v * 1_000_000, a);
  return 2 * Number(isqrt((BigInt(d) * 1_000_000_000_000n) / BigInt(a)));
}

/** Caches move times by distance: plans repeat the same few distances millions of times. */
export class MoveTimes {
  readonly #cache = [new Map<number, number>(), new Map<number, number>()];
  readonly #engine = new Map<number, number>();
  constructor(private readonly machine: MotionModel) {
    if (!LINK_BAUDS.includes(machine.linkBaud)) throw new RangeError(`the printhead link has no speed ${machine.linkBaud} baud (nano.md "Link speed")`);
  }

  axis(axis: 0 | 1, d: number): number {
    const cache = this.#cache[axis];
    let t = cache.get(d);
    if (t === undefined) {
      t = moveTimeUs(d, this.machine.vmaxUmS[axis], this.machine.accelUmS2[axis]);
      cache.set(d, t);
    }
    return t;
  }

  /** The step engine's move by (dx, dy) steps, µs. */
  engine(dx: number, dy: number): number {
    const key = Math.abs(dx) * 0x100000000 + Math.abs(dy);
    let t = this.#engine.get(key);
    if (t === undefined) {
      t = engineMoveUs(this.machine, Math.abs(dx), Math.abs(dy));
      this.#engine.set(key, t);
    }
    return t;
  }

  /** The step engine's move between two bed positions (µm), µs. */
  move(x: number, y: number, fromX: number, fromY: number): number {
    const m = this.machine;
    return this.engine(axisSteps(m, 0, x) - axisSteps(m, 0, fromX), axisSteps(m, 1, y) - axisSteps(m, 1, fromY));
  }

  /**
   * The time model's cost of one stop (protocol/planner.md "Time model"): the step engine's move
   * from (fromX, fromY) to (x, y) in µm, the settle after a move, the per-stop overhead, its F line
   * on the wire, and its longest exposure (`us`: its four durations).
   */
  stop(x: number, y: number, fromX: number, fromY: number, us: ArrayLike<number>): number {
    const m = this.machine;
    return this.stopSteps(axisSteps(m, 0, x) - axisSteps(m, 0, fromX), axisSteps(m, 1, y) - axisSteps(m, 1, fromY), us);
  }

  /** The same after a move of (dx, dy) steps: the one rule every planner prices a stop by (stopCostStepsUs in C++). */
  stopSteps(dx: number, dy: number, us: ArrayLike<number>): number {
    const move = this.engine(dx, dy);
    return move + (move > 0 ? this.machine.settleUs : 0) + this.machine.overheadUs + fireLineUs(us, this.machine.linkBaud) + Math.max(us[0], us[1], us[2], us[3]);
  }
}
