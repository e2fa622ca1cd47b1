// The dry run's thermal forecast: the plan's stops played through the shared head model
// (machine/head-thermal.ts) in the planner's time model, with the Mega's temperature readings every
// 500 ms and its rules for them (machine/pacing.ts): an unpaced job pauses when a reading reaches a soft
// limit; a paced one waits before a stop, or before a pass on the move and its move, while a reading
// is near one. The simulated printer runs the same model and rules, so the forecast is what it then
// does (thermal-forecast.test.ts, paced-scan.test.ts). A scan job is played pass by pass with its
// LEDs' switch times, a mixed job pass by pass either way.

import { passDurationUs, passSwitches } from '../planner/job-plan';
import type { MixedPlan, Plan, ScanPass, ScanPlan } from '../planner/plan';
import { axisSteps, stopCostUs } from '../planner/planner-wasm';
import type { MotionModel } from '../planner/time-model';
import { HEAD_THERMAL, HeadThermal, type HeadThermalModel } from '../machine/head-thermal';
import { overSoftLimit, paceWaits, READING_PERIOD_US } from '../machine/pacing';

export interface ThermalRun {
  /** The hottest each sensor gets, °C (up to the pause, for a job that pauses). */
  peakC: number[];
  /** Where the job would pause: the stop under way (its index, from 0) when a reading first shows `sensor` at its soft limit. */
  pause: { stop: number; sensor: number; atUs: number; c: number } | null;
  /** Time a paced job waits to cool, µs. */
  waitUs: number;
  /** The job's time with those waits, µs; for a job that pauses, its time until the pause. */
  totalUs: number;
}

export interface ForecastOptions {
  /** The Mega's soft limits, °C, per sensor. */
  limitsC: number[];
  /** The head's temperatures as the job starts (the printer's last report); the model's ambient if absent. */
  startC?: number[];
  model?: HeadThermalModel;
  paced: boolean;
}

/** Where on the bed the plan's cells lie: the job header's origin and pitch, µm. */
export interface PlanPlace {
  originUm: [number, number];
  pitchUm: [number, number];
}

/** The head and the Mega's readings through a job's timeline: what each forecast plays its job into. */
function forecastHead(o: ForecastOptions) {
  const head = new HeadThermal(o.model ?? HEAD_THERMAL, o.startC);
  const limits = o.limitsC.map((c) => Math.round(c * 10));
  const s = { t: 0, nextRead: READING_PERIOD_US, reading: head.deciC(), stop: 0, pause: null as ThermalRun['pause'], waitUs: 0 };

  /** Holds `lit` for `dt`, taking the Mega's readings on the way; false once a reading pauses the job. */
  const hold = (dt: number, lit: number): boolean => {
    while (s.t + dt >= s.nextRead) {
      const step = s.nextRead - s.t;
      head.advance(step, lit);
      s.t = s.nextRead;
      dt -= step;
      s.nextRead += READING_PERIOD_US;
      s.reading = head.deciC();
      const over = overSoftLimit(s.reading, limits);
      if (over >= 0) {
        s.pause = { stop: s.stop, sensor: over, atUs: s.t, c: s.reading[over] / 10 };
        return false;
      }
    }
    head.advance(dt, lit);
    s.t += dt;
    return true;
  };

  /** A paced job waits, LEDs off, until a reading shows the head cool enough (the Mega's Settle phase); false if it paused. */
  const paceWait = (): boolean => {
    if (!o.paced || !paceWaits(s.reading, limits, false)) return true;
    const from = s.t;
    while (paceWaits(s.reading, limits, true)) if (!hold(s.nextRead - s.t, 0)) return false;
    s.waitUs += s.t - from;
    return true;
  };

  const result = (): ThermalRun => ({ peakC: head.peak.slice(), pause: s.pause, waitUs: s.waitUs, totalUs: s.t });
  return { s, hold, paceWait, result };
}

export function forecastThermal(plan: Plan, place: PlanPlace, machine: MotionModel, o: ForecastOptions): ThermalRun {
  const { s, hold, paceWait, result } = forecastHead(o);
  let x = axisSteps(machine, 0, machine.startUm[0]), y = axisSteps(machine, 1, machine.startUm[1]);
  const d = [0, 0, 0, 0];
  for (s.stop = 0; s.stop < plan.count; s.stop++) {
    const stop = s.stop;
    const nx = axisSteps(machine, 0, place.originUm[0] + plan.hx[stop] * place.pitchUm[0]);
    const ny = axisSteps(machine, 1, place.originUm[1] + plan.hy[stop] * place.pitchUm[1]);
    let longest = 0;
    for (let k = 0; k < 4; k++) longest = Math.max(longest, (d[k] = plan.durations[stop * 4 + k]));
    if (!hold(stopCostUs(machine, nx - x, ny - y, d) - longest, 0)) break;
    x = nx, y = ny;
    if (!paceWait() || !exposeStop(hold, d)) break;
  }
  return result();
}

/** A stop's exposure: every LED lit at once, each off after its own time `d[k]`; false if the job paused. */
function exposeStop(hold: (dt: number, lit: number) => boolean, d: ArrayLike<number>): boolean {
  const longest = Math.max(d[0], d[1], d[2], d[3]);
  let at = 0;
  while (at < longest) {
    let lit = 0, next = longest;
    for (let k = 0; k < 4; k++) if (d[k] > at) (lit |= 1 << k), (next = Math.min(next, d[k]));
    if (!hold(next - at, lit)) return false;
    at = next;
  }
  return true;
}

/** A pass on the move after its move and overhead: each LED lit exactly over its on-intervals; false if the job paused. */
function exposeStroke(hold: (dt: number, lit: number) => boolean, pass: ScanPass): boolean {
  const stroke = pass.strokeUs;
  let at = -pass.markUs, lit = 0; // µs after the pass's start mark, as the stroke runs
  for (const sw of passSwitches(pass)) {
    if (!hold(sw.atUs - at, lit)) return false;
    at = sw.atUs;
    lit = sw.mask;
  }
  return hold(stroke - pass.markUs - at, lit);
}

/**
 * A mixed job (planner.md "Mixed mode") played pass by pass: a pass on the move as forecastScanThermal
 * plays it, a pass of stops as forecastThermal does, each stop's time the one planMixed priced (the
 * head kept in steps). A pause is reported at the step under way (`stop` counts the Mega's steps: a
 * stop, or a pass on the move).
 */
export function forecastMixedThermal(mixed: MixedPlan, place: PlanPlace, machine: MotionModel, o: ForecastOptions): ThermalRun {
  const { s, hold, paceWait, result } = forecastHead(o);
  let x = axisSteps(machine, 0, machine.startUm[0]), y = axisSteps(machine, 1, machine.startUm[1]);
  s.stop = 0;
  for (const p of mixed.passes) {
    if (p.scan) {
      if (!paceWait() || !hold(p.scanUs - p.pass.strokeUs, 0) || !exposeStroke(hold, p.pass)) break; // the Mega paces before the pass's move
      x = p.pass.stopSteps;
      y = axisSteps(machine, 1, place.originUm[1] + p.hy * place.pitchUm[1]);
      s.stop++;
      continue;
    }
    for (const [hx, hy, ...d] of p.stops) {
      const nx = axisSteps(machine, 0, place.originUm[0] + hx * place.pitchUm[0]), ny = axisSteps(machine, 1, place.originUm[1] + hy * place.pitchUm[1]);
      // The stop's cost less its exposure: the move, the settle, the overhead, its F line.
      if (!hold(stopCostUs(machine, nx - x, ny - y, d) - Math.max(d[0], d[1], d[2], d[3]), 0) || !paceWait() || !exposeStop(hold, d)) return result();
      x = nx, y = ny;
      s.stop++;
    }
  }
  return result();
}

/**
 * A scan job (exposure on the move) played the same way, pass by pass: the move to its run-up,
 * settle and overhead with the LEDs off, then the pass with each LED lit exactly over its
 * on-intervals, so the head warms with the LEDs' real duty (on-time against the pass's wall time).
 * A pause is reported at the pass under way (`stop` counts passes).
 */
export function forecastScanThermal(scan: ScanPlan, place: PlanPlace, machine: MotionModel, o: ForecastOptions): ThermalRun {
  const { s, hold, paceWait, result } = forecastHead(o);
  for (s.stop = 0; s.stop < scan.passes.length; s.stop++) {
    const pass = scan.passes[s.stop];
    const stroke = passDurationUs(scan, pass);
    if (!paceWait()) break; // the Mega paces between passes, before the move to the next
    if (!hold(pass.wallUs - stroke, 0)) break; // the move, the overhead, the Q that ends the pass
    if (!exposeStroke(hold, pass)) break;
  }
  return result();
}
