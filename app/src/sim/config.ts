// The Mega's configuration keys and defaults (M850 / M500-M503, CONFIG.TXT on SD), shared by the simulated printer.

import type { Machine } from '../planner/time-model';

export const CONFIG_DEFAULTS: Record<string, string> = {
  'steps_per_mm.x': '80',
  'steps_per_mm.y': '80',
  'steps_per_mm.z': '400',
  'bed.x': '200',
  'bed.y': '200',
  'bed.z': '40',
  'speed.travel': '100',
  'speed.z': '10',
  'speed.jog_slow': '5',
  'speed.jog_fast': '50',
  'speed.home': '40',
  'accel.x': '2000',
  'accel.y': '1500',
  'accel.z': '200',
  'settle_ms': '2',
  'stop_overhead_us': '4300',
  'invert.x': '0',
  'invert.y': '0',
  'invert.z': '0',
  'pitch.x': '50',
  'pitch.y': '50',
  'led.offset.0': '0,0',
  'led.offset.1': '0,1',
  'led.offset.2': '0,2',
  'led.offset.3': '0,3',
  'led.irradiance.0': '30000',
  'led.irradiance.1': '30000',
  'led.irradiance.2': '30000',
  'led.irradiance.3': '30000',
  'led.gain.0': '1000',
  'led.gain.1': '1000',
  'led.gain.2': '1000',
  'led.gain.3': '1000',
  'thermal.limit.0': '55',
  'thermal.limit.1': '55',
  'thermal.limit.2': '55',
  'thermal.limit.3': '55',
  'thermal.limit.4': '50',
  'thermal.limit.5': '50',
  'thermal.coeff': '0',
  'esp.port': '2',
  'light.pin': '57',
  'mesh.nx': '3',
  'mesh.ny': '3',
  'mesh.margin': '10',
  'report.position_ms': '0',
};

/** Each key's range, both ends included, and the numbers it takes (CONFIG.md "range"). */
export const CONFIG_RANGES: Record<string, [number, number, 'decimal' | 'whole' | 'pair']> = {
  'steps_per_mm.x': [1, 2000, 'decimal'],
  'steps_per_mm.y': [1, 2000, 'decimal'],
  'steps_per_mm.z': [1, 10000, 'decimal'],
  'bed.x': [1, 2000, 'decimal'],
  'bed.y': [1, 2000, 'decimal'],
  'bed.z': [1, 500, 'decimal'],
  'speed.travel': [1, 500, 'decimal'],
  'speed.z': [0.1, 100, 'decimal'],
  'speed.jog_slow': [0.1, 100, 'decimal'],
  'speed.jog_fast': [1, 500, 'decimal'],
  'speed.home': [1, 200, 'decimal'],
  'accel.x': [10, 20000, 'decimal'],
  'accel.y': [10, 20000, 'decimal'],
  'accel.z': [1, 5000, 'decimal'],
  'settle_ms': [0, 1000, 'whole'],
  'stop_overhead_us': [0, 100000, 'whole'],
  'invert.x': [0, 1, 'whole'],
  'invert.y': [0, 1, 'whole'],
  'invert.z': [0, 1, 'whole'],
  'pitch.x': [1, 100000, 'whole'],
  'pitch.y': [1, 100000, 'whole'],
  'led.offset.0': [-4096, 4096, 'pair'],
  'led.offset.1': [-4096, 4096, 'pair'],
  'led.offset.2': [-4096, 4096, 'pair'],
  'led.offset.3': [-4096, 4096, 'pair'],
  'led.irradiance.0': [1, 2000000, 'whole'],
  'led.irradiance.1': [1, 2000000, 'whole'],
  'led.irradiance.2': [1, 2000000, 'whole'],
  'led.irradiance.3': [1, 2000000, 'whole'],
  'led.gain.0': [1, 10000, 'whole'],
  'led.gain.1': [1, 10000, 'whole'],
  'led.gain.2': [1, 10000, 'whole'],
  'led.gain.3': [1, 10000, 'whole'],
  'thermal.limit.0': [0, 60, 'decimal'],
  'thermal.limit.1': [0, 60, 'decimal'],
  'thermal.limit.2': [0, 60, 'decimal'],
  'thermal.limit.3': [0, 60, 'decimal'],
  'thermal.limit.4': [0, 60, 'decimal'],
  'thermal.limit.5': [0, 60, 'decimal'],
  'thermal.coeff': [-1000, 1000, 'whole'],
  'esp.port': [2, 3, 'whole'],
  'light.pin': [0, 69, 'whole'],
  'mesh.nx': [3, 9, 'whole'],
  'mesh.ny': [3, 9, 'whole'],
  'mesh.margin': [0, 100, 'decimal'],
  'report.position_ms': [0, 60000, 'whole'],
};

/** A key's value as a number; the defaults make every key parse. */
export function num(config: Record<string, string>, key: string): number {
  return Number(config[key] ?? CONFIG_DEFAULTS[key]);
}

/** The Mega's step engine steps an axis no faster than this (`kMaxStepRate`, firmware/mega/src/step_profile.h). */
export const MAX_STEP_RATE = 16000;

/**
 * An axis's top speed in µm/s: its setting (`speed.travel`, or `speed.z`), or what the step engine
 * runs at the axis's steps/mm if that is less, as the Mega holds every move to it.
 */
export function topSpeedUmS(config: Record<string, string>, axis: number): number {
  const setting = Math.round(num(config, axis === 2 ? 'speed.z' : 'speed.travel') * 1000);
  const stepsMilli = Math.round(num(config, ['steps_per_mm.x', 'steps_per_mm.y', 'steps_per_mm.z'][axis]) * 1000);
  return Math.min(setting, Math.floor((MAX_STEP_RATE * 1_000_000) / stepsMilli));
}

/**
 * The printhead link's speed this firmware's Mega plans and runs every job at (kJobLinkBaud in
 * firmware/mega/src/printhead_link.h: it raises the link to 250000 once the Nano is known).
 */
export const BOARD_LINK_BAUD = 250000;

/** The motion the planner's time model prices (protocol/planner.md), from the settings, starting at `startUm`. */
export function motionOf(config: Record<string, string>, startUm: [number, number] = [0, 0], linkBaud = BOARD_LINK_BAUD): Machine {
  return {
    vmaxUmS: [topSpeedUmS(config, 0), topSpeedUmS(config, 1)],
    accelUmS2: [num(config, 'accel.x') * 1000, num(config, 'accel.y') * 1000],
    settleUs: num(config, 'settle_ms') * 1000,
    overheadUs: num(config, 'stop_overhead_us'),
    startUm,
    stepsMilli: [Math.round(num(config, 'steps_per_mm.x') * 1000), Math.round(num(config, 'steps_per_mm.y') * 1000)],
    linkBaud,
  };
}

/** Validates one M850 assignment: a known key and a well-formed value inside the key's range. */
export function validConfig(key: string, value: string): boolean {
  const range = CONFIG_RANGES[key];
  if (range === undefined) return false;
  const [lo, hi, kind] = range;
  const inside = (v: number) => v >= lo && v <= hi;
  if (kind === 'pair') return /^-?\d+,-?\d+$/.test(value) && value.split(',').every((v) => inside(Number(v)));
  if (!/^-?\d+(\.\d+)?$/.test(value)) return false;
  const milli = Math.round(Number(value) * 1000); // held in thousandths, as on the Mega
  return inside(milli / 1000) && (kind !== 'whole' || milli % 1000 === 0);
}
