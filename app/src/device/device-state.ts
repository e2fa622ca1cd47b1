// One typed view of the printer, folded from every report line (protocol/mega.md §4), whatever the transport.

import type { JobState, ProbeState, Reply } from '../protocol/dialect-reply';

export interface JobProgress {
  state: JobState;
  file?: string;
  stop?: number;
  stops?: number;
  elapsedS?: number;
  remainingS?: number;
  reason?: string;
  /** Streamed (M828, no SD card): exposed as it arrives, and it cannot be resumed. */
  stream?: boolean;
  /** Paced (mega.md "Pacing"), and now waiting for the head to cool before its next stop. */
  paced?: boolean;
  cooling?: boolean;
}

export interface Fault {
  code: number;
  message: string;
  atMs: number;
}

export interface DeviceState {
  firmware: string | null;
  window: number;
  /** Head position in µm. */
  position: [number, number, number] | null;
  /** The sensors, °C × 10. Their soft limits are settings (`thermal.limit.<i>`, Printer.config), not reports. */
  deciC: number[] | null;
  probe: ProbeState | null;
  lastProbeZUm: number | null;
  /** LEDs lit, from the job reports. */
  leds: number;
  job: JobProgress | null;
  /** Every fault reported since the link opened (the log), newest last. */
  faults: Fault[];
  /**
   * The faults that are a state of the machine, one per code: a silent printhead (E30) until it
   * answers again (Printer clears it on an M105 answer); an over-temperature, a sensor fault or a
   * refused exposure (E31-E33) until a job runs or ends. The others (a probe alarm, a failed homing)
   * are events: they are in `faults` only.
   */
  activeFaults: Fault[];
  /** The latest `TEST:` result. */
  selfTest: { mode: 'quick' | 'full'; fields: Record<string, string> } | null;
  mesh: string[];
}

export function emptyState(): DeviceState {
  return {
    firmware: null, window: 1, position: null, deciC: null, probe: null, lastProbeZUm: null,
    leds: 0, job: null, faults: [], activeFaults: [], selfTest: null, mesh: [],
  };
}

const MAX_FAULTS = 50;
/** E30 printhead not responding, E31 over-temperature (protocol/errors.csv). */
export const PRINTHEAD_SILENT = 30;
export const OVERTEMP = 31;
/** The printhead's faults that pause a job, and that a job which runs (or ends) leaves behind. */
const JOB_FAULTS = new Set([OVERTEMP, 32, 33]);
const ENDED = new Set(['done', 'aborted', 'failed', 'idle']);

/**
 * A fault's words with the unit its reading has: the Mega says "over-temperature T3 60.2 (soft
 * limit)" in °C (mega.md "Pacing"), and a person reads "T3 60.2 °C".
 */
export function withUnits(message: string): string {
  return message.replace(/^(over-temperature T\d) (-?\d+(?:\.\d+)?)(?= \(|$)/, '$1 $2 °C');
}

/** Drops a fault the machine no longer has (`code`), e.g. E30 once the printhead answers again. */
export function clearFault(s: DeviceState, code: number): boolean {
  if (!s.activeFaults.some((a) => a.code === code)) return false;
  s.activeFaults = s.activeFaults.filter((a) => a.code !== code);
  return true;
}

/** Applies one parsed line to the state; returns true when something changed. */
export function applyReport(s: DeviceState, r: Reply, nowMs: number): boolean {
  switch (r.kind) {
    case 'firmware': s.firmware = r.name; return true;
    case 'cap': if (r.name === 'RX_WINDOW') s.window = r.value; return true;
    case 'temps': s.deciC = r.deciC; return true;
    case 'position': s.position = r.um; return true;
    case 'probe': s.probe = r.state; return true;
    case 'probePoint': s.lastProbeZUm = r.um[2]; s.position = r.um; return true;
    case 'test': s.selfTest = { mode: r.mode, fields: r.fields }; return true;
    case 'job': {
      const f = r.fields;
      const before = s.job?.state;
      // A job that runs (the Mega started or continued it: nothing over its limit), or ends, leaves
      // the faults that paused it behind.
      if ((before !== 'running' && r.state === 'running') || (before !== undefined && before !== r.state && ENDED.has(r.state))) {
        s.activeFaults = s.activeFaults.filter((a) => !JOB_FAULTS.has(a.code));
      }
      const [stop, stops] = (f.stop ?? '').split('/').map(Number);
      s.job = {
        state: r.state,
        file: f.file,
        stop: Number.isFinite(stop) ? stop : undefined,
        stops: Number.isFinite(stops) ? stops : undefined,
        elapsedS: f.elapsed !== undefined ? Number(f.elapsed) : undefined,
        remainingS: f.remaining !== undefined ? Number(f.remaining) : undefined,
        reason: f.reason,
        stream: f.mode === 'stream',
        paced: f.paced === '1',
        cooling: f.cooling === '1',
      };
      if (f.leds !== undefined) s.leds = Number(f.leds);
      if (r.state !== 'running') s.leds = 0;
      return true;
    }
    case 'fault': {
      const fault = { code: r.code, message: withUnits(r.message), atMs: nowMs };
      s.faults = [...s.faults, fault].slice(-MAX_FAULTS);
      if (r.code === PRINTHEAD_SILENT || JOB_FAULTS.has(r.code)) s.activeFaults = [...s.activeFaults.filter((a) => a.code !== r.code), fault];
      return true;
    }
    case 'other':
      if (r.text.startsWith('MESH:grid')) s.mesh = [r.text];
      else if (r.text.startsWith('MESH:row')) s.mesh = [...s.mesh, r.text];
      else return false;
      return true;
    default:
      return false;
  }
}
