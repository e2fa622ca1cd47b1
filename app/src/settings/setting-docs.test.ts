import { describe, expect, it } from 'vitest';
import { CONFIG_DEFAULTS } from '../machine/config';
import { SimHost } from '../sim/sim-host.fixture';
import { isToggle, SETTING_DOCS, settingProblem } from './setting-docs';

describe('settings, as CONFIG.md describes them', () => {
  it('has every key of the table, each with a name in words, a unit, a range and a description', () => {
    const docs = [...SETTING_DOCS.values()];
    expect(docs.map((d) => d.key)).toEqual(Object.keys(CONFIG_DEFAULTS));
    for (const d of docs) {
      expect(d.name, d.key).not.toBe(d.key);
      expect(d.unit, d.key).not.toBe('');
      expect(d.description.split(' ').length, d.key).toBeGreaterThan(1);
    }
    expect(SETTING_DOCS.get('pitch.x')).toMatchObject({ name: 'X cell pitch', unit: 'µm', range: '1 to 100000 whole', description: 'default cell pitch along X for jobs made on the printer' });
    expect(SETTING_DOCS.get('thermal.limit.3')?.description).toBe('the Mega\'s soft limit for sensor A3: no job starts or continues above it');
    expect(SETTING_DOCS.get('led.gain.2')?.description).toBe('calibration gain of LED 2');
  });
  it('says in words what CONFIG.md leaves to other documents: no description names a file (issue 29, item 14)', () => {
    for (const d of SETTING_DOCS.values()) expect(d.description, d.key).not.toMatch(/\.md\b/);
    expect(SETTING_DOCS.get('led.offset.2')?.description).toBe('LED 2 offset dx,dy from the head origin, in cells: with the head over a cell, LED 2 exposes the cell dx across and dy down from it');
    expect(SETTING_DOCS.get('led.irradiance.0')?.description).toMatch(/^measured irradiance of LED 0, for dose targets: a dose asked in µJ\/cm² becomes an exposure time/);
    expect(SETTING_DOCS.get('thermal.coeff')?.description).toMatch(/^thermal compensation c: each exposure is lengthened by c × 0\.01 % for every °C/);
  });
  it('shows the 0-or-1 settings as toggles, and only those', () => {
    const toggles = [...SETTING_DOCS.values()].filter(isToggle).map((d) => d.key);
    expect(toggles).toEqual(['invert.x', 'invert.y', 'invert.z']);
    for (const key of toggles) for (const v of ['0', '1']) expect(settingProblem(key, v)).toBeNull(); // what a toggle writes
  });
  it('says what is wrong with a value, and agrees with what the printer takes', () => {
    expect(settingProblem('pitch.x', 'abc')).toBe('not a number');
    expect(settingProblem('pitch.x', '0')).toBe('out of range: 1 to 100000');
    expect(settingProblem('pitch.x', '2.5')).toBe('a whole number');
    expect(settingProblem('led.offset.1', '0;1')).toBe('two whole numbers with a comma, dx,dy');
    expect(settingProblem('bed.x', '150.5')).toBeNull();
    expect(settingProblem('accel.w', '1')).toBe('not a setting this printer knows');
    // The referee is the Mega's own C++ (the simulated printer): M850 takes a value, or answers E50.
    const h = new SimHost();
    // report.position_ms is left out: a period under 50 ms (which M154 refuses, but the key takes) makes
    // the position reports fill the Mega's transmit ring and starve every reply, this M850's too. A known
    // firmware bug, not yet mended: its first fix left out M155's reports under the app's own traffic.
    for (const key of Object.keys(CONFIG_DEFAULTS).filter((k) => k !== 'report.position_ms')) {
      for (const v of ['abc', '0', '1', '-1', '2.5', '55', '60', '60.001', '100000', '0,1', '-1,3', '0,4097', '5000,0', '1,2', CONFIG_DEFAULTS[key]]) {
        const taken = !h.cmd(`M850 ${key} ${v}`).some((l) => /E50 config/.test(l));
        expect(settingProblem(key, v) === null, `${key} = ${v}`).toBe(taken);
        if (taken) h.cmd(`M850 ${key} ${CONFIG_DEFAULTS[key]}`); // one key off its default at a time
      }
    }
  });
});
