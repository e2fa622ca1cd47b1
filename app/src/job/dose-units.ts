// The job's full dose as a time (ms a cell) or as energy (mJ/cm², what resist datasheets give). A
// dose in mJ/cm² goes to the printer as the job's `target` with each LED's irradiance, from the
// machine's calibration (`led.irradiance.N`, µW/cm², firmware/mega/CONFIG.md), and the Mega
// times each LED by it (protocol/job.md): µJ/cm² ÷ µW/cm² = s. Without a calibration, ms only.

import type { Dose } from '../protocol/job-types';
import { roundDiv } from '../planner/dose';
import { CONFIG_DEFAULTS } from '../machine/config';

export type Calibration = { irradianceUWcm2: number[] } | { missing: string };

const KEYS = [0, 1, 2, 3].map((i) => `led.irradiance.${i}`);

/**
 * The LEDs' irradiance as the printer reports it (`M503`). The firmware's default is no
 * measurement: a dose in mJ/cm² through it would be a guess, so it counts as no calibration.
 */
export function calibrationOf(config: Record<string, string> | null): Calibration {
  if (!config) return { missing: 'connect to the printer to read its LEDs\' irradiance' };
  const values = KEYS.map((k) => Number(config[k]));
  if (!values.every((v) => Number.isInteger(v) && v > 0)) return { missing: 'the printer does not report its LEDs\' irradiance (led.irradiance.0–3)' };
  if (KEYS.every((k) => config[k] === CONFIG_DEFAULTS[k]))
    return { missing: 'the LEDs\' irradiance (led.irradiance.0–3) is still the firmware\'s default, not a measurement; measure it and set it in Settings' };
  return { irradianceUWcm2: values };
}

/** µJ/cm² for the job's `target`: whole, 1 … 100 000 000. */
export const targetOf = (mJcm2: number) => Math.min(100_000_000, Math.max(1, Math.round(mJcm2 * 1000)));

/** The time, ms, the Mega gives a full cell for a dose at one LED's irradiance (rounded to its µs). */
export function msFor(mJcm2: number, irradianceUWcm2: number): number {
  return roundDiv(targetOf(mJcm2) * 1_000_000, irradianceUWcm2) / 1000;
}

/** The dose in mJ/cm² that `ms` gives at an irradiance, to three figures. */
export function mJcm2For(ms: number, irradianceUWcm2: number): number {
  return +((ms * irradianceUWcm2) / 1e6).toPrecision(3);
}

/** "4.00 ms", or "3.90–4.10 ms" when the LEDs differ. */
export function msWords(mJcm2: number, c: { irradianceUWcm2: number[] }): string {
  const ms = c.irradianceUWcm2.map((i) => msFor(mJcm2, i));
  const lo = Math.min(...ms), hi = Math.max(...ms), f = (v: number) => v.toPrecision(3);
  return lo === hi ? `${f(lo)} ms` : `${f(lo)}–${f(hi)} ms`;
}

/** The job's dose: energy through the calibration when it is set in mJ/cm² and calibrated, else the time. */
export function doseOf(fullMs: number, mJcm2: number | null, c: Calibration): Dose {
  if (mJcm2 !== null && 'irradianceUWcm2' in c) return { map: 'linear', targetUJcm2: targetOf(mJcm2), irradianceUWcm2: c.irradianceUWcm2 };
  return { map: 'linear', fullUs: Math.round(fullMs * 1000) };
}
