// What each setting is, for people: its name in words, unit, range and a one-line description,
// read from the Mega's one table of keys (firmware/mega/CONFIG.md) when the app is built, and
// what is wrong with a value typed for it.

import configMd from '../../../firmware/mega/CONFIG.md?raw';

export interface SettingDoc {
  key: string;
  name: string;
  unit: string;
  lo: number;
  hi: number;
  kind: 'decimal' | 'whole' | 'pair';
  /** The range as CONFIG.md words it: `1 to 2000`, `0 to 1000 whole`, `-4096 to 4096 each`. */
  range: string;
  description: string;
}

const AXIS = (k: string) => k.at(-1)!.toUpperCase();
const INDEX = (k: string) => k.slice(k.lastIndexOf('.') + 1);
const SENSORS = ['LED 0', 'LED 1', 'LED 2', 'LED 3', 'driver', 'frame'];

/** Names in words, by key or by the key's family (its part before the last dot). */
const NAMES: Record<string, (key: string) => string> = {
  steps_per_mm: (k) => `${AXIS(k)} steps per mm`,
  bed: (k) => `${AXIS(k)} travel`,
  'speed.travel': () => 'Travel speed',
  'speed.z': () => 'Z speed',
  'speed.jog_slow': () => 'Slow jog speed',
  'speed.jog_fast': () => 'Fast jog speed',
  'speed.home': () => 'Homing speed',
  accel: (k) => `${AXIS(k)} acceleration`,
  settle_ms: () => 'Settle time',
  stop_overhead_us: () => 'Time per stop',
  invert: (k) => `Reverse ${AXIS(k)}`,
  pitch: (k) => `${AXIS(k)} cell pitch`,
  'led.offset': (k) => `LED ${INDEX(k)} offset`,
  'led.irradiance': (k) => `LED ${INDEX(k)} irradiance`,
  'led.gain': (k) => `LED ${INDEX(k)} gain`,
  'thermal.limit': (k) => `Soft limit, ${SENSORS[Number(INDEX(k))]} sensor`,
  'thermal.coeff': () => 'Thermal compensation',
  'esp.port': () => 'ESP serial port',
  'light.pin': () => 'Work light pin',
  'mesh.nx': () => 'Mesh points along X',
  'mesh.ny': () => 'Mesh points along Y',
  'mesh.margin': () => 'Mesh margin',
  'report.position_ms': () => 'Position report period',
};

export function nameOf(key: string): string | null {
  const family = key.includes('.') ? key.slice(0, key.lastIndexOf('.')) : key;
  return (NAMES[key] ?? NAMES[family])?.(key) ?? null;
}

/**
 * What CONFIG.md leaves to another document ("(planner.md)"), said in words: a user does not know
 * those files (issue 29, item 14). By the key's family; the LED's number follows the key.
 */
const REFERRED: Record<string, (n: string) => string> = {
  'led.offset': (n) => `, in cells: with the head over a cell, LED ${n} exposes the cell dx across and dy down from it`,
  'led.irradiance': () => ': a dose asked in µJ/cm² becomes an exposure time from it (dose ÷ irradiance)',
  'thermal.coeff': () => ": each exposure is lengthened by c × 0.01 % for every °C its LED's sensor is above the job's reference temperature, and shortened below it; 0 is off",
};

/** A description (its markdown links already plain) with its "(job.md)" said in words instead. */
export function inWords(key: string, description: string): string {
  const bare = description.replace(/\s*\([\w./-]+\.md\)/g, '');
  return bare === description ? description : bare + (REFERRED[key.replace(/\.\d+$/, '')]?.(INDEX(key)) ?? '');
}

const strip = (cell: string) => cell.trim().replace(/`/g, '').replace(/\[([^\]]+)\]\([^)]*\)/g, '$1').replace(/\s*\(\)\s*$/, '');

/** The rows of CONFIG.md's "Keys" table. */
export function parseConfigTable(md: string): SettingDoc[] {
  const rows = md.slice(md.indexOf('## Keys')).split('\n').filter((l) => /^\| `/.test(l));
  const docs: SettingDoc[] = [];
  for (const row of rows) {
    const [key, unit, , range, cited] = row.split('|').slice(1, -1).map(strip);
    const what = inWords(key, cited);
    const m = /^(-?[\d.]+) to (-?[\d.]+)(?: (whole|each))?$/.exec(range);
    if (!m) throw new Error(`CONFIG.md: cannot read the range of ${key}: ${range}`);
    docs.push({ key, name: nameOf(key) ?? key, unit, lo: Number(m[1]), hi: Number(m[2]), kind: m[3] === 'whole' ? 'whole' : m[3] === 'each' ? 'pair' : 'decimal', range, description: what });
  }
  // A row after the first of its family says only what differs ("LED 1", "sensor A1"): it takes
  // the first row's words with the first one's subject changed.
  for (const d of docs) {
    const first = docs.find((f) => f.key.replace(/\d+$/, '') === d.key.replace(/\d+$/, '') && /\.0$/.test(f.key));
    if (!first || first === d || d.description.split(' ').length > 3 || d.description.length >= first.description.length) continue;
    const n = INDEX(d.key);
    d.description = first.description.replace(/\b(LED |A)0\b/g, `$1${n}`);
  }
  return docs;
}

export const SETTING_DOCS: ReadonlyMap<string, SettingDoc> = new Map(parseConfigTable(configMd).map((d) => [d.key, d]));

/** A setting that is on (1) or off (0), shown as a checkbox: the Reverse X/Y/Z pins. */
export function isToggle(doc: SettingDoc | undefined): boolean {
  return !!doc && doc.kind === 'whole' && doc.lo === 0 && doc.hi === 1;
}

/** What is wrong with `value` for `key`, in words, or null if the printer will take it (CONFIG.md "Values"). */
export function settingProblem(key: string, value: string, doc = SETTING_DOCS.get(key)): string | null {
  if (!doc) return 'not a setting this printer knows';
  const inRange = (v: number) => v >= doc.lo && v <= doc.hi;
  if (doc.kind === 'pair') {
    if (!/^-?\d+,-?\d+$/.test(value)) return 'two whole numbers with a comma, dx,dy';
    return value.split(',').every((v) => inRange(Number(v))) ? null : `each must be ${doc.lo} to ${doc.hi}`;
  }
  if (!/^-?\d+(\.\d+)?$/.test(value)) return 'not a number';
  const milli = Math.round(Number(value) * 1000); // kept in thousandths, as on the Mega
  if (!inRange(milli / 1000)) return `out of range: ${doc.lo} to ${doc.hi}`;
  if (doc.kind === 'whole' && milli % 1000 !== 0) return 'a whole number';
  return null;
}
