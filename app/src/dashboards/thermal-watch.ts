// Warnings for a sensor warming faster than the LEDs' duty explains: a fan that stopped, a heatsink
// come loose, a driver running hot. The expected rate comes from the same thermal model as the dry run.

import type { HeadThermalModel } from '../machine/head-thermal';

export interface Sample {
  tS: number;
  celsius: number[];
  exposing: boolean;
}

export interface RateWarning {
  sensor: number;
  observedCPerS: number;
  expectedCPerS: number;
}

/** The span a slope is fitted over, the least of it that must be there, and the tolerated excess. */
export const WATCH_SPAN_S = 30;
const MIN_SPAN_S = 10;
export const MARGIN_C_PER_S = 0.15;

/** Least-squares slope of y over t. */
function slope(t: number[], y: number[]): number {
  const n = t.length;
  const mt = t.reduce((a, b) => a + b, 0) / n, my = y.reduce((a, b) => a + b, 0) / n;
  let num = 0, den = 0;
  for (let i = 0; i < n; i++) {
    num += (t[i] - mt) * (y[i] - my);
    den += (t[i] - mt) ** 2;
  }
  return den ? num / den : 0;
}

/**
 * `duty` is each LED's share of time lit while a job exposes (the job's plan), or null when it is
 * not known (a job the app did not start): then a running job may explain any warming of the LEDs.
 */
export function rateWarnings(samples: Sample[], duty: number[] | null, model: HeadThermalModel): RateWarning[] {
  if (samples.length < 3 || samples.at(-1)!.tS - samples[0].tS < MIN_SPAN_S) return [];
  const t = samples.map((s) => s.tS);
  const lit = samples.filter((s) => s.exposing).length / samples.length;
  const d = [0, 1, 2, 3].map((k) => lit * (duty ? duty[k] ?? 0 : 1));
  const mean = [0, 1, 2, 3, 4, 5].map((k) => samples.reduce((a, s) => a + s.celsius[k], 0) / samples.length);
  const cooling = (k: number) => model.coolingPerS * (mean[k] - model.ambientC[k]);
  const expected = [
    ...d.map((dk, k) => model.heatingCPerS * dk - cooling(k)),
    model.heatingCPerS * model.driverShare * d.reduce((a, b) => a + b, 0) - cooling(4),
    -cooling(5),
  ];
  const out: RateWarning[] = [];
  for (let k = 0; k < 6; k++) {
    const observed = slope(t, samples.map((s) => s.celsius[k]));
    const explained = Math.max(expected[k], 0);
    if (Number.isFinite(observed) && observed > explained + MARGIN_C_PER_S) out.push({ sensor: k, observedCPerS: observed, expectedCPerS: explained });
  }
  return out;
}
