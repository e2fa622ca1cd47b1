// Validates a POST /print body (protocol/esp.md, print-job.schema.json) into a PrintJob and whether
// to run it paced, or an HTTP error.

import { STRATEGY_NAMES, type PrintJob } from './job-types';

export const ESP_LIMITS = { maxBody: 1_200_000, maxCells: 262_144 } as const;

export type PrintRequestResult =
  /** `paced`: the body's "paced" (false without it), not part of the job; the hub starts it with `M24 P1` (mega.md "Pacing"). */
  | { status: 202; job: PrintJob; paced: boolean }
  | { status: 400 | 413; error: 'bad_json' | 'bad_job' | 'too_large'; message: string; path?: string };

class Invalid extends Error {
  constructor(readonly path: string, message: string, readonly status: 400 | 413 = 400) {
    super(message);
  }
}

type Obj = Record<string, unknown>;

function object(v: unknown, path: string, keys: string[], required: string[]): Obj {
  if (typeof v !== 'object' || v === null || Array.isArray(v)) throw new Invalid(path, 'must be an object');
  for (const k of Object.keys(v)) if (!keys.includes(k)) throw new Invalid(`${path}/${k}`, 'unknown field');
  for (const k of required) if (!(k in v)) throw new Invalid(`${path}/${k}`, 'missing');
  return v as Obj;
}

function integer(v: unknown, path: string, lo: number, hi: number): number {
  if (typeof v !== 'number' || !Number.isInteger(v) || v < lo || v > hi) {
    throw new Invalid(path, `must be an integer ${lo}..${hi}`);
  }
  return v;
}

function array(v: unknown, path: string, min: number, max: number): unknown[] {
  if (!Array.isArray(v) || v.length < min || v.length > max) {
    throw new Invalid(path, min === max ? `must be an array of ${min}` : `must be an array of ${min}..${max}`);
  }
  return v;
}

function xy(v: unknown, path: string, lo: number, hi: number): { x: number; y: number } {
  const o = object(v, path, ['x', 'y'], ['x', 'y']);
  return { x: integer(o.x, `${path}/x`, lo, hi), y: integer(o.y, `${path}/y`, lo, hi) };
}

function validate(root: unknown): { job: PrintJob; paced: boolean } {
  const o = object(root, '', ['name', 'grid', 'pitchUm', 'originUm', 'dose', 'leds', 'thermal', 'strategy', 'paced', 'gridData'],
    ['grid', 'pitchUm', 'originUm', 'dose', 'leds', 'strategy', 'gridData']);
  if ('name' in o && (typeof o.name !== 'string' || !/^[A-Za-z0-9_.-]{1,31}$/.test(o.name))) {
    throw new Invalid('/name', 'must be 1-31 of A-Z a-z 0-9 _ . -');
  }
  const g = object(o.grid, '/grid', ['cols', 'rows'], ['cols', 'rows']);
  const cols = integer(g.cols, '/grid/cols', 1, 4096);
  const rows = integer(g.rows, '/grid/rows', 1, 4096);
  if (cols * rows > ESP_LIMITS.maxCells) {
    throw new Invalid('/grid', `${cols}x${rows} is over ${ESP_LIMITS.maxCells} cells; send larger jobs over USB`, 413);
  }
  const pitchUm = xy(o.pitchUm, '/pitchUm', 1, 100000);
  const originUm = xy(o.originUm, '/originUm', 0, 10000000);

  const d = object(o.dose, '/dose', ['map', 'level', 'fullUs', 'targetUJcm2', 'irradianceUWcm2'], ['map']);
  if (d.map !== 'linear' && d.map !== 'threshold') throw new Invalid('/dose/map', 'must be linear or threshold');
  if (d.map === 'threshold' && !('level' in d)) throw new Invalid('/dose/level', 'threshold needs a level');
  if (d.map === 'linear' && 'level' in d) throw new Invalid('/dose/level', 'linear takes no level');
  const level = d.map === 'threshold' ? integer(d.level, '/dose/level', 1, 255) : undefined;
  const hasTarget = 'targetUJcm2' in d || 'irradianceUWcm2' in d;
  if ('fullUs' in d === hasTarget) throw new Invalid('/dose', 'give fullUs, or targetUJcm2 with irradianceUWcm2');
  let dose: PrintJob['dose'];
  if ('fullUs' in d) {
    dose = { map: d.map, level, fullUs: integer(d.fullUs, '/dose/fullUs', 1, 10000000) };
  } else {
    if (!('targetUJcm2' in d)) throw new Invalid('/dose/targetUJcm2', 'missing');
    if (!('irradianceUWcm2' in d)) throw new Invalid('/dose/irradianceUWcm2', 'missing');
    const target = integer(d.targetUJcm2, '/dose/targetUJcm2', 1, 100000000);
    const irr = array(d.irradianceUWcm2, '/dose/irradianceUWcm2', 4, 4)
      .map((v, i) => integer(v, `/dose/irradianceUWcm2/${i}`, 1, 10000000));
    dose = { map: d.map, level, targetUJcm2: target, irradianceUWcm2: irr };
  }
  if (level === undefined) delete dose.level;

  const l = object(o.leds, '/leds', ['offsets', 'gainPermille'], ['offsets']);
  const offsets = array(l.offsets, '/leds/offsets', 4, 4).map((p, i) => {
    const pair = array(p, `/leds/offsets/${i}`, 2, 2);
    return [integer(pair[0], `/leds/offsets/${i}/0`, -4096, 4096), integer(pair[1], `/leds/offsets/${i}/1`, -4096, 4096)] as [number, number];
  });
  const leds: PrintJob['leds'] = { offsets };
  if ('gainPermille' in l) {
    leds.gainPermille = array(l.gainPermille, '/leds/gainPermille', 4, 4).map((v, i) => integer(v, `/leds/gainPermille/${i}`, 1, 10000));
  }

  const job: PrintJob = { grid: { cols, rows }, pitchUm, originUm, dose, leds, strategy: { name: 'raster' }, gridData: [] };
  if ('name' in o) job.name = o.name as string;
  if ('thermal' in o) {
    const t = object(o.thermal, '/thermal', ['coeffCentiPctPerC', 'refDeciC'], ['coeffCentiPctPerC', 'refDeciC']);
    job.thermal = { coeffCentiPctPerC: integer(t.coeffCentiPctPerC, '/thermal/coeffCentiPctPerC', -1000, 1000), refDeciC: integer(t.refDeciC, '/thermal/refDeciC', -400, 1250) };
  }
  const s = object(o.strategy, '/strategy', ['name', 'seed'], ['name']);
  if (!(STRATEGY_NAMES as readonly unknown[]).includes(s.name)) {
    throw new Invalid('/strategy/name', 'must be raster, serpentine, shortest, random or scan');
  }
  job.strategy = { name: s.name as PrintJob['strategy']['name'] };
  if ('seed' in s) job.strategy.seed = integer(s.seed, '/strategy/seed', 0, 4294967295);
  if ('paced' in o && typeof o.paced !== 'boolean') throw new Invalid('/paced', 'must be true or false');
  const paced = o.paced === true;

  const data = array(o.gridData, '/gridData', rows, rows);
  job.gridData = data.map((row, r) => {
    const cells = array(row, `/gridData/${r}`, cols, cols);
    const out = new Uint8Array(cols);
    for (let c = 0; c < cols; c++) out[c] = integer(cells[c], `/gridData/${r}/${c}`, 0, 255);
    return out;
  });
  return { job, paced };
}

/** `contentLength` is the request's header, checked before the body is read. */
export function validatePrintRequest(body: string, contentLength = body.length): PrintRequestResult {
  if (contentLength > ESP_LIMITS.maxBody) {
    return { status: 413, error: 'too_large', message: `body over ${ESP_LIMITS.maxBody} bytes` };
  }
  let root: unknown;
  try {
    root = JSON.parse(body);
  } catch (e) {
    return { status: 400, error: 'bad_json', message: (e as Error).message };
  }
  try {
    return { status: 202, ...validate(root) };
  } catch (e) {
    if (!(e instanceof Invalid)) throw e;
    if (e.status === 413) return { status: 413, error: 'too_large', message: e.message };
    return { status: 400, error: 'bad_job', message: `${e.path || '/'}: ${e.message}`, path: e.path };
  }
}
