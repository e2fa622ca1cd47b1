// What of the simulated printer the browser keeps between page loads (issue 17, item 5): the card
// (the job's checkpoint is a file on it, as the firmware writes it), the Mega's EEPROM, the Nano's
// start count and a running job, and how it is read back. A store that a broken write, another
// version or a hand left behind is checked field by field: what does not hold up is dropped, and the
// note says what.

import { EEPROM_BYTES } from './wasm/printer-module';
import type { SavedMachine } from './sim-printer';

export const MACHINE_VERSION = 2;

/** A job from the card that was running when the record was kept: when (wall ms), at what speed, paced or not. */
export interface RunningJob {
  atMs: number;
  speed: number;
  paced: boolean;
}

/** The small record kept when the EEPROM, the start count or the running job change; the card's files are kept apart. */
export interface MachineRecord {
  version: typeof MACHINE_VERSION;
  eeprom: Uint8Array;
  boots: number;
  running: RunningJob | null;
}

export interface Kept {
  saved: SavedMachine | null;
  running: RunningJob | null;
  /** What could not be read and was dropped, in words; null when all was well (or nothing was kept yet). */
  note: string | null;
}

export function machineRecord(saved: SavedMachine, running: RunningJob | null): MachineRecord {
  return { version: MACHINE_VERSION, eeprom: saved.eeprom ?? new Uint8Array(EEPROM_BYTES).fill(0xff), boots: saved.boots, running };
}

const isObject = (v: unknown): v is Record<string, unknown> => typeof v === 'object' && v !== null && !Array.isArray(v);
const count = (v: unknown): v is number => Number.isInteger(v) && (v as number) >= 0 && (v as number) < 65535;

function cardOf(v: unknown): [string, string][] | null {
  if (!Array.isArray(v)) return null;
  const files = v.filter((e): e is [string, string] => Array.isArray(e) && e.length === 2 && typeof e[0] === 'string' && e[0] !== '' && typeof e[1] === 'string');
  return files.length === v.length ? files : null;
}

function runningOf(v: unknown): RunningJob | null | undefined {
  if (v === null) return null;
  if (!isObject(v) || !Number.isFinite(v.atMs) || typeof v.paced !== 'boolean') return undefined;
  if (!Number.isFinite(v.speed) || (v.speed as number) < 1 || (v.speed as number) > 1000) return undefined;
  return { atMs: v.atMs as number, speed: v.speed as number, paced: v.paced };
}

/** The machine record, or why it does not hold up. */
function recordOf(v: unknown): MachineRecord | string {
  if (isObject(v) && v.version === 1) return 'it was kept by an earlier version of the simulated printer, so it has its default settings and nothing to resume';
  const bad = 'its settings and checkpoint could not be read, so it has its defaults and nothing to resume';
  if (!isObject(v) || v.version !== MACHINE_VERSION || !count(v.boots)) return bad;
  if (!(v.eeprom instanceof Uint8Array) || v.eeprom.length !== EEPROM_BYTES) return bad;
  const running = runningOf(v.running);
  if (running === undefined) return bad;
  return { version: MACHINE_VERSION, eeprom: v.eeprom, boots: v.boots as number, running };
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
  if (typeof record === 'string') notes.push(record);
  const kept = typeof record === 'string' ? null : record;
  // A record without its checkpoint's card (or a card without the record) resumes nothing: the
  // firmware finds no checkpoint, or says why it cannot take it, when asked.
  return {
    saved: { files, eeprom: kept?.eeprom ?? null, boots: kept?.boots ?? 0 },
    running: files.length ? (kept?.running ?? null) : null,
    note: notes.length ? `The simulated printer kept in this browser was damaged: ${notes.join('; ')}.` : null,
  };
}
