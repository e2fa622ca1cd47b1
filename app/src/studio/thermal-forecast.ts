// The dry run's thermal forecast: the plan's stops played through the shared head model
// (sim/head-thermal.ts) in the planner's time model, with the Mega's temperature readings every
// 500 ms and its rules for them (sim/pacing.ts): an unpaced job pauses when a reading reaches a soft
// limit; a paced one waits before a stop while a reading is near one. The simulated printer runs the
// same model and rules, so the forecast is what it then does (thermal-forecast.test.ts).

import type { Plan } from '../planner/planner';
import { MoveTimes, type Machine } from '../planner/time-model';
import { HEAD_THERMAL, HeadThermal, type HeadThermalModel } from '../sim/head-thermal';
import { overSoftLimit, paceWaits, READING_PERIOD_US } from '../sim/pacing';

export interface ThermalRun {
  /** The hottest each sensor gets, °C (up to the pause, for a job that pauses). */
  peakC: number[];
  /** Where the job would pause: the stop under way when a reading first shows `sensor` at its soft limit. */
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

export function forecastThermal(plan: Plan, place: PlanPlace, machine: Machine, o: ForecastOptions): ThermalRun {
  const head = new HeadThermal(o.model ?? HEAD_THERMAL, o.startC);
  const limits = o.limitsC.map((c) => Math.round(c * 10));
  const moves = new MoveTimes(machine);
  let t = 0;
  let nextRead = READING_PERIOD_US;
  let reading = head.deciC();
  let stop = 0;
  let pause: ThermalRun['pause'] = null;
  let waitUs = 0;

  /** Holds `lit` for `dt`, taking the Mega's readings on the way; false once a reading pauses the job. */
  const hold = (dt: number, lit: number): boolean => {
    while (t + dt >= nextRead) {
      const step = nextRead - t;
      head.advance(step, lit);
      t = nextRead;
      dt -= step;
      nextRead += READING_PERIOD_US;
      reading = head.deciC();
      const over = overSoftLimit(reading, limits);
      if (over >= 0) {
        pause = { stop, sensor: over, atUs: t, c: reading[over] / 10 };
        return false;
      }
    }
    head.advance(dt, lit);
    t += dt;
    return true;
  };

  let x = machine.startUm[0], y = machine.startUm[1];
  const d = [0, 0, 0, 0];
  run: for (stop = 0; stop < plan.count; stop++) {
    const nx = place.originUm[0] + plan.hx[stop] * place.pitchUm[0];
    const ny = place.originUm[1] + plan.hy[stop] * place.pitchUm[1];
    let longest = 0;
    for (let k = 0; k < 4; k++) longest = Math.max(longest, (d[k] = plan.durations[stop * 4 + k]));
    if (!hold(moves.stop(nx, ny, x, y, longest) - longest, 0)) break;
    x = nx, y = ny;
    if (o.paced && paceWaits(reading, limits, false)) {
      // Wait, LEDs off, until a reading shows the head cool enough (the Mega's Settle phase).
      const from = t;
      while (paceWaits(reading, limits, true)) if (!hold(nextRead - t, 0)) break run;
      waitUs += t - from;
    }
    // The exposure: every LED of the stop lit at once, each off after its own time.
    let at = 0;
    while (at < longest) {
      let lit = 0, next = longest;
      for (let k = 0; k < 4; k++) if (d[k] > at) (lit |= 1 << k), (next = Math.min(next, d[k]));
      if (!hold(next - at, lit)) break run;
      at = next;
    }
  }
  return { peakC: head.peak.slice(), pause, waitUs, totalUs: t };
}
