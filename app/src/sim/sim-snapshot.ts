// What of the simulated printer the browser keeps between page loads (issue 17, item 5): the card, the
// job's checkpoint, the EEPROM, the start count and a running job, and how it is read back. A store
// that a broken write, another version or a hand left behind is checked field by field: what does
// not hold up is dropped, and the note says what.

import { validConfig } from './config';
import type { Xyz } from './motion';
import type { Checkpoint } from './sd-card';
import type { SavedMachine, SimPrinter } from './sim-printer';

export const MACHINE_VERSION = 1;

/** A job that was running when the record was kept: where the head stood, when (wall ms), at what speed. */
export interface RunningJob {
  pos: Xyz;
  atMs: number;
  speed: number;
}

/** The small record kept at the pace of the checkpoints; the card's files are kept apart, when they change. */
export interface MachineRecord {
  version: typeof MACHINE_VERSION;
  checkpoint: Checkpoint | null;
  eeprom: Record<string, string> | null;
  boots: number;
  running: RunningJob | null;
}

export interface Kept {
  saved: SavedMachine | null;
  running: RunningJob | null;
  /** What could not be read and was dropped, in words; null when all was well (or nothing was kept yet). */
  note: string | null;
}

/** A job from the card runs and has a checkpoint: a reload should find it run on. Streams have no checkpoint. */
export function jobRunning(p: SimPrinter): boolean {
  const { job } = p.mega;
  return job.state === 'running' && !job.streaming && p.sd.checkpoint?.file === job.file; // not an older job's checkpoint
}

export function machineRecord(p: SimPrinter, running: RunningJob | null): MachineRecord {
  const cp = p.sd.checkpoint;
  return { version: MACHINE_VERSION, checkpoint: cp && { ...cp }, eeprom: p.mega.eeprom && { ...p.mega.eeprom }, boots: p.boots, running };
}

const isObject = (v: unknown): v is Record<string, unknown> => typeof v === 'object' && v !== null && !Array.isArray(v);
const count = (v: unknown): v is number => Number.isInteger(v) && (v as number) >= 0;

function cardOf(v: unknown): [string, string][] | null {
  if (!Array.isArray(v)) return null;
  const files = v.filter((e): e is [string, string] => Array.isArray(e) && e.length === 2 && typeof e[0] === 'string' && e[0] !== '' && typeof e[1] === 'string');
  return files.length === v.length ? files : null;
}

function checkpointOf(v: unknown): Checkpoint | null | undefined {
  if (v === null) return null;
  if (!isObject(v) || typeof v.file !== 'string' || ![v.done, v.stops, v.boot, v.fires].every(count) || (v.done as number) > (v.stops as number)) return undefined;
  return { file: v.file, done: v.done as number, stops: v.stops as number, boot: v.boot as number, fires: v.fires as number };
}

function eepromOf(v: unknown): Record<string, string> | null | undefined {
  if (v === null) return null;
  if (!isObject(v) || !Object.entries(v).every(([k, x]) => typeof x === 'string' && validConfig(k, x))) return undefined;
  return { ...(v as Record<string, string>) };
}

function runningOf(v: unknown): RunningJob | null | undefined {
  if (v === null) return null;
  if (!isObject(v) || !Array.isArray(v.pos) || v.pos.length !== 3 || !v.pos.every(Number.isFinite)) return undefined;
  if (!Number.isFinite(v.atMs) || !Number.isFinite(v.speed) || (v.speed as number) < 1 || (v.speed as number) > 1000) return undefined;
  return { pos: [...v.pos] as Xyz, atMs: v.atMs as number, speed: v.speed as number };
}

/** The machine record, or undefined if any of it does not hold up. */
function recordOf(v: unknown): MachineRecord | undefined {
  if (!isObject(v) || v.version !== MACHINE_VERSION || !count(v.boots)) return undefined;
  const checkpoint = checkpointOf(v.checkpoint);
  const eeprom = eepromOf(v.eeprom);
  const running = runningOf(v.running);
  if (checkpoint === undefined || eeprom === undefined || running === undefined) return undefined;
  return { version: MACHINE_VERSION, checkpoint, eeprom, boots: v.boots as number, running };
}

/** Reads back what the store held under `card` and `machine` (undefined: never kept). */
export function readKept(card: unknown, machine: unknown): Kept {
  if (card === undefined && machine === undefined) return { saved: null, running: null, note: null };
  const notes: string[] = [];
  let files = card === undefined ? [] : cardOf(card);
  if (!files) {
    notes.push('its card could not be read, so the card is empty');
    files = [];
  }
  const record = machine === undefined ? null : recordOf(machine);
  if (record === undefined) notes.push('its settings and checkpoint could not be read, so it has its defaults and nothing to resume');
  let checkpoint = record?.checkpoint ?? null;
  if (checkpoint && !files.some(([name]) => name === checkpoint!.file)) {
    notes.push(`its checkpoint names ${checkpoint.file}, which is not on its card, so there is nothing to resume`);
    checkpoint = null;
  }
  return {
    saved: { files, checkpoint, eeprom: record?.eeprom ?? null, boots: record?.boots ?? 0 },
    running: checkpoint ? (record?.running ?? null) : null,
    note: notes.length ? `The simulated printer kept in this browser was damaged: ${notes.join('; ')}.` : null,
  };
}
