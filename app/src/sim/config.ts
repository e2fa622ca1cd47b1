// The Mega's configuration keys and defaults (M850 / M500-M503, CONFIG.TXT on SD), shared by the simulated printer.

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
  'stop_overhead_us': '1500',
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
  'light.pin': '4',
  'mesh.nx': '3',
  'mesh.ny': '3',
  'mesh.margin': '10',
  'report.position_ms': '0',
};

/** A key's value as a number; the defaults make every key parse. */
export function num(config: Record<string, string>, key: string): number {
  return Number(config[key] ?? CONFIG_DEFAULTS[key]);
}

/** Validates one M850 assignment: a known key and a value of the default's kind. */
export function validConfig(key: string, value: string): boolean {
  const def = CONFIG_DEFAULTS[key];
  if (def === undefined) return false;
  if (def.includes(',')) return /^-?\d+,-?\d+$/.test(value);
  return /^-?\d+(\.\d+)?$/.test(value);
}
