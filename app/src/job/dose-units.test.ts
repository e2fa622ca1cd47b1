import { describe, expect, it } from 'vitest';
import { CONFIG_DEFAULTS } from '../machine/config';
import { calibrationOf, doseOf, mJcm2For, msFor, msWords } from './dose-units';

const calibrated = { ...CONFIG_DEFAULTS, 'led.irradiance.0': '2000000', 'led.irradiance.1': '1950000', 'led.irradiance.2': '2000000', 'led.irradiance.3': '2050000' };

describe('the dose in mJ/cm²', () => {
  it('needs the LEDs\' irradiance measured: none, missing or the firmware\'s default is no calibration', () => {
    expect(calibrationOf(null)).toEqual({ missing: expect.stringMatching(/connect to the printer/) });
    const { 'led.irradiance.2': _, ...without } = calibrated;
    expect(calibrationOf(without)).toEqual({ missing: expect.stringMatching(/does not report/) });
    expect(calibrationOf(CONFIG_DEFAULTS)).toEqual({ missing: expect.stringMatching(/still the firmware's default, not a measurement/) });
    expect(calibrationOf(calibrated)).toEqual({ irradianceUWcm2: [2000000, 1950000, 2000000, 2050000] });
  });

  it('is a time through each LED\'s irradiance, as the Mega rounds it: µJ/cm² ÷ µW/cm² = s', () => {
    expect(msFor(8, 2_000_000)).toBe(4); // 8 mJ/cm² at 2 W/cm²
    expect(msFor(100, 30_000)).toBeCloseTo(3333.333, 3);
    expect(mJcm2For(4, 2_000_000)).toBe(8);
    const c = calibrationOf(calibrated) as { irradianceUWcm2: number[] };
    expect(msWords(8, c)).toBe('3.90–4.10 ms');
    expect(msWords(8, { irradianceUWcm2: [2e6, 2e6, 2e6, 2e6] })).toBe('4.00 ms');
  });

  it('goes to the printer as the job\'s target with the irradiances, or as a time without a calibration', () => {
    const c = calibrationOf(calibrated);
    expect(doseOf(4, 8, c)).toEqual({ map: 'linear', targetUJcm2: 8000, irradianceUWcm2: [2000000, 1950000, 2000000, 2050000] });
    expect(doseOf(4, null, c)).toEqual({ map: 'linear', fullUs: 4000 });
    expect(doseOf(4, 8, calibrationOf(null))).toEqual({ map: 'linear', fullUs: 4000 });
  });
});
