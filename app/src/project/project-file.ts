// A project as a file: JSON with the painted cells packed and every picture or drawing embedded as
// the file it was imported from, so it opens anywhere with nothing beside it. Opening checks every
// field and says which one is wrong; nothing of the project open in the editor is lost by a bad
// file. Version 2 added the resist polarity, turned and mirrored objects, the coverage threshold
// in percent (version 1's `level` in 255ths), SVG drawings and a dose in mJ/cm², and later boards (Gerber and Excellon files, kind 'board') that
// older apps refuse by name, as they refuse the strategy `scan` (exposure on the move); version 1 opens.

import { MAX_SIDE } from '../studio/grid/grid';
import { HALFTONES, type Halftone } from '../studio/image/halftones';
import type { Tone } from '../studio/image/adjust';
import { BOARD_LAYER_KINDS, DRILL_CLEARS, type BoardLayerKind, type DrillClear, type StudioObject, type Turn } from '../studio/objects/objects';
import type { Polarity } from '../studio/objects/raster';
import { STRATEGY_NAMES, type StrategyName } from '../protocol/job-types';
import { isBlank, packCells, unpackCells } from './cells-codec';
import { MAX_PROJECT_BYTES, ProjectError } from './project-error';

export { MAX_PROJECT_BYTES, ProjectError };

export const PROJECT_FORMAT = 'uv-exposure-project';
export const PROJECT_VERSION = 2;
/** How a board's files are embedded (app/src/pcb/board-artwork.ts's BOARD_SRC_PREFIX, which loads on demand). */
const BOARD_SRC = 'data:application/vnd.uv-exposure.board+json;base64,';
const STRATEGIES = STRATEGY_NAMES;

export interface Project {
  name: string;
  machine: { bedMm: { x: number; y: number }; pitchUm: { x: number; y: number } };
  /** `mJcm2`: the full dose was set as energy; `fullMs` is then its time for LED 0, used where the LEDs' calibration is not known. */
  /** `auto`: the fastest order for the drawing (job-plan.ts); older apps refuse it by name. */
  exposure: { fullMs: number; strategy: StrategyName | 'auto'; mJcm2?: number };
  polarity: Polarity;
  /** The painted cells, cols × rows, row 0 first. */
  paint: { cols: number; rows: number; cells: Uint8Array };
  objects: StudioObject[];
}

export async function encodeProject(p: Project, savedAt = new Date()): Promise<string> {
  const empty = await isBlank(p.paint.cells);
  return JSON.stringify({
    format: PROJECT_FORMAT,
    version: PROJECT_VERSION,
    name: p.name,
    savedAt: savedAt.toISOString(),
    machine: p.machine,
    exposure: p.exposure,
    polarity: p.polarity,
    paint: { cols: p.paint.cols, rows: p.paint.rows, cells: empty ? null : await packCells(p.paint.cells) },
    objects: p.objects,
  });
}

type Json = Record<string, unknown>;

function fail(path: string, what: string): never {
  throw new ProjectError(`${path} ${what}`);
}

function obj(v: unknown, path: string): Json {
  if (typeof v !== 'object' || v === null || Array.isArray(v)) fail(path, 'must be an object');
  return v as Json;
}

function numIn(v: unknown, path: string, min: number, max: number, integer = false): number {
  if (typeof v !== 'number' || !Number.isFinite(v) || v < min || v > max || (integer && !Number.isInteger(v)))
    fail(path, `must be ${integer ? 'a whole number' : 'a number'} from ${min} to ${max}`);
  return v;
}

function str(v: unknown, path: string, max: number): string {
  if (typeof v !== 'string' || v.length > max) fail(path, `must be text of at most ${max} characters`);
  return v;
}

function bool(v: unknown, path: string): boolean {
  if (typeof v !== 'boolean') fail(path, 'must be true or false');
  return v;
}

function xy(v: unknown, path: string, min: number, max: number): { x: number; y: number } {
  const o = obj(v, path);
  return { x: numIn(o.x, `${path}.x`, min, max), y: numIn(o.y, `${path}.y`, min, max) };
}

/** An artwork's halftone, threshold and tone. */
function artworkLook(o: Json, path: string, version: number): { halftone: Halftone; threshold: number; tone: Tone } {
  const halftone = o.halftone as Halftone;
  if (!HALFTONES.includes(halftone)) fail(`${path}.halftone`, `must be one of ${HALFTONES.join(', ')}`);
  const t = obj(o.tone, `${path}.tone`);
  const tone = { invert: bool(t.invert, `${path}.tone.invert`), contrast: numIn(t.contrast, `${path}.tone.contrast`, -100, 100), gamma: numIn(t.gamma, `${path}.tone.gamma`, 0.05, 20) };
  // Version 1 kept the threshold as a darkness level in 255ths: the same cut in percent.
  const threshold = version === 1 ? (numIn(o.level, `${path}.level`, 1, 255, true) * 100) / 255 : numIn(o.threshold, `${path}.threshold`, 0.1, 100);
  return { halftone, threshold, tone };
}

function object(v: unknown, path: string, cols: number, rows: number, version: number): StudioObject {
  const o = obj(v, path);
  const box = {
    id: numIn(o.id, `${path}.id`, 1, 1e9, true),
    x: numIn(o.x, `${path}.x`, -MAX_SIDE, cols, true),
    y: numIn(o.y, `${path}.y`, -MAX_SIDE, rows, true),
    w: numIn(o.w, `${path}.w`, 1, 2 * MAX_SIDE, true),
    h: numIn(o.h, `${path}.h`, 1, 2 * MAX_SIDE, true),
    ...(o.turn !== undefined && { turn: numIn(o.turn, `${path}.turn`, 0, 3, true) as Turn }),
    ...(o.mirror !== undefined && { mirror: bool(o.mirror, `${path}.mirror`) }),
  };
  const dose = () => numIn(o.dose, `${path}.dose`, 0, 255, true);
  switch (o.kind) {
    case 'image':
    case 'svg': {
      const src = str(o.src, `${path}.src`, MAX_PROJECT_BYTES);
      const svg = o.kind === 'svg';
      if (!(svg ? /^data:image\/svg\+xml;base64,/ : /^data:image\/[\w.+-]+;base64,/).test(src)) fail(`${path}.src`, `must be ${svg ? 'an SVG drawing' : 'a picture'} embedded as a data: URL`);
      return { kind: svg ? 'svg' : 'image', ...box, name: str(o.name, `${path}.name`, 255), src, ...artworkLook(o, path, version) };
    }
    case 'board': {
      const src = str(o.src, `${path}.src`, MAX_PROJECT_BYTES);
      if (!src.startsWith(BOARD_SRC)) fail(`${path}.src`, "must be a board's files embedded as a data: URL");
      if (!Array.isArray(o.layers)) fail(`${path}.layers`, 'must be a list');
      const layers = o.layers.map((v, i) => {
        const l = obj(v, `${path}.layers[${i}]`);
        if (!BOARD_LAYER_KINDS.includes(l.kind as BoardLayerKind)) fail(`${path}.layers[${i}].kind`, `must be one of ${BOARD_LAYER_KINDS.join(', ')}`);
        return { file: str(l.file, `${path}.layers[${i}].file`, 255), kind: l.kind as BoardLayerKind, expose: bool(l.expose, `${path}.layers[${i}].expose`) };
      });
      const drillClear = o.drillClear as DrillClear;
      if (!DRILL_CLEARS.includes(drillClear)) fail(`${path}.drillClear`, `must be one of ${DRILL_CLEARS.join(', ')}`);
      if (!Array.isArray(o.marks)) fail(`${path}.marks`, 'must be a list');
      const marks = o.marks.map((m, i) => xy(m, `${path}.marks[${i}]`, -10_000, 10_000));
      const leftOut = o.leftOut !== undefined && { leftOut: bool(o.leftOut, `${path}.leftOut`) };
      const copperGuessed = o.copperGuessed !== undefined && { copperGuessed: str(o.copperGuessed, `${path}.copperGuessed`, 255) };
      return { kind: 'board', ...box, name: str(o.name, `${path}.name`, 255), src, ...artworkLook(o, path, version), layers, drillClear, marks, ...leftOut, ...copperGuessed };
    }
    case 'text':
      return { kind: 'text', ...box, text: str(o.text, `${path}.text`, 10_000), font: str(o.font, `${path}.font`, 200), bold: bool(o.bold, `${path}.bold`), dose: dose() };
    case 'frame':
      return { kind: 'frame', ...box, line: numIn(o.line, `${path}.line`, 0, MAX_SIDE, true), dose: dose() };
    default:
      fail(`${path}.kind`, 'must be image, svg, board, text or frame');
  }
}

export async function decodeProject(text: string): Promise<Project> {
  let raw: unknown;
  try {
    raw = JSON.parse(text);
  } catch (e) {
    throw new ProjectError(`this is not a project file: ${(e as Error).message}`);
  }
  const f = obj(raw, 'the file');
  if (f.format !== PROJECT_FORMAT) throw new ProjectError('this is not a project file (no "format": "uv-exposure-project")');
  const version = f.version;
  if (version !== 1 && version !== PROJECT_VERSION) throw new ProjectError(`this project is version ${String(f.version)}; this app opens versions 1 to ${PROJECT_VERSION}`);
  const m = obj(f.machine, 'machine');
  const machine = { bedMm: xy(m.bedMm, 'machine.bedMm', 1, 10_000), pitchUm: xy(m.pitchUm, 'machine.pitchUm', 1, 10_000) };
  const e = obj(f.exposure, 'exposure');
  const strategy = e.strategy as StrategyName | 'auto';
  if (strategy !== 'auto' && !STRATEGIES.includes(strategy)) fail('exposure.strategy', `must be one of ${STRATEGIES.join(', ')}, auto`);
  const exposure = {
    fullMs: numIn(e.fullMs, 'exposure.fullMs', 0.001, 60_000),
    strategy,
    ...(e.mJcm2 !== undefined && { mJcm2: numIn(e.mJcm2, 'exposure.mJcm2', 0.001, 100_000) }),
  };
  const polarity = (f.polarity ?? 'negative') as Polarity; // version 1: the artwork was exposed
  if (polarity !== 'negative' && polarity !== 'positive') fail('polarity', 'must be negative or positive');
  const p = obj(f.paint, 'paint');
  const cols = numIn(p.cols, 'paint.cols', 1, MAX_SIDE, true), rows = numIn(p.rows, 'paint.rows', 1, MAX_SIDE, true);
  let cells: Uint8Array = new Uint8Array(cols * rows);
  if (p.cells !== null) {
    try {
      cells = await unpackCells(str(p.cells, 'paint.cells', MAX_PROJECT_BYTES), cols * rows);
    } catch (err) {
      throw err instanceof ProjectError ? err : new ProjectError(`paint.cells ${(err as Error).message}`);
    }
  }
  if (!Array.isArray(f.objects)) fail('objects', 'must be a list');
  const objects = f.objects.map((o, i) => object(o, `objects[${i}]`, cols, rows, version));
  const ids = new Set(objects.map((o) => o.id));
  if (ids.size !== objects.length) fail('objects', 'has two objects with the same id');
  return { name: str(f.name, 'name', 255), machine, exposure, polarity, paint: { cols, rows, cells }, objects };
}
