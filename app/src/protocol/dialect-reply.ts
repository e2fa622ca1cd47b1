// Replies and reports of the Mega dialect, typed and parsed (host side); their canonical lines are
// reply-format.ts's (Mega side).

import { parseMilli } from './dialect-number';
import { crc16Hex } from './crc16';
import { parseDeciC, SENSOR_COUNT } from './nano';

export type JobState = 'idle' | 'uploading' | 'ready' | 'running' | 'paused' | 'done' | 'aborted' | 'failed' | 'interrupted';
export type ProbeState = 'triggered' | 'open' | 'alarm' | 'deployed' | 'stowed';
type Xyz = [number, number, number];

export type Reply =
  | { kind: 'ok'; n?: number; p?: number; b?: number }
  | { kind: 'error'; code: number; message: string }
  | { kind: 'resend'; n: number }
  | { kind: 'temps'; deciC: number[] }
  | { kind: 'position'; um: Xyz; steps: Xyz }
  | { kind: 'job'; state: JobState; fields: Record<string, string> }
  | { kind: 'probe'; state: ProbeState }
  | { kind: 'probePoint'; um: Xyz }
  | { kind: 'test'; mode: 'quick' | 'full'; fields: Record<string, string> }
  | { kind: 'fault'; code: number; message: string }
  | { kind: 'echo'; text: string }
  | { kind: 'busy' }
  | { kind: 'start' }
  | { kind: 'firmware'; name: string; protocol: number }
  | { kind: 'cap'; name: string; value: number }
  | { kind: 'other'; text: string }
  | DoseReport;

/**
 * What the printhead delivered to one stop, or to one program of a pass on the move (mega.md "Dose
 * reports"): each LED's on-time in µs as the Nano timed it, and for a stop what was sent.
 */
export interface DoseReport {
  kind: 'dose';
  stop: number;
  program: number;
  exposure: number;
  onUs: number[];
  planUs?: number[];
  /** Cut short (a fault, a reset): the stop is exposed again, with `again`. */
  cut: boolean;
  /** The stop had light before in this job: its cells got it twice. */
  again: boolean;
}

const JOB_STATES = new Set(['idle', 'uploading', 'ready', 'running', 'paused', 'done', 'aborted', 'failed', 'interrupted']);
const PROBE_STATES = new Set(['triggered', 'open', 'alarm', 'deployed', 'stowed']);
const MM = '(-?[0-9]{1,7}\\.[0-9]{3})';
const POSITION = new RegExp(`^X:${MM} Y:${MM} Z:${MM} E:${MM} Count X:(-?[0-9]{1,10}) Y:(-?[0-9]{1,10}) Z:(-?[0-9]{1,10})$`);
const BED = new RegExp(`^Bed X: ${MM} Y: ${MM} Z: ${MM}$`);
const U32 = '([0-9]{1,10})';
const FOUR = `${U32},${U32},${U32},${U32}`;
const DOSE = new RegExp(`^DOSE:stop=${U32} prog=([0-9]{1,5}) exp=${U32} on=${FOUR}(?: plan=${FOUR})?( cut=1)?( again=1)?$`);
const DECI = '(-?[0-9]{1,3}\\.[0-9])';
const TEMP_PAIR = new RegExp(`^S([0-5]):${DECI} /0\\.0$`);

/** `key=value` words; null if any word is not that shape. */
function parseFields(rest: string): Record<string, string> | null {
  const fields: Record<string, string> = {};
  for (const word of rest.split(' ').filter(Boolean)) {
    const m = /^([a-z_]+)=(\S+)$/.exec(word);
    if (!m) return null;
    fields[m[1]] = m[2];
  }
  return fields;
}

function parseTemps(line: string): Reply | null {
  const words = line.split(' ');
  // `T:<hottest> /0.0` then six `S<i>:<v> /0.0` pairs: nothing heats, so no target (mega.md §4)
  if (words.length !== 2 + SENSOR_COUNT * 2 || !/^T:-?[0-9]{1,3}\.[0-9]$/.test(words[0]) || words[1] !== '/0.0') return null;
  const deciC: number[] = [];
  for (let i = 0; i < SENSOR_COUNT; i++) {
    const m = TEMP_PAIR.exec(`${words[2 + i * 2]} ${words[3 + i * 2]}`);
    if (!m || Number(m[1]) !== i) return null;
    deciC.push(parseDeciC(m[2])!);
  }
  return { kind: 'temps', deciC };
}

function parseDose(line: string): DoseReport | null {
  const m = DOSE.exec(line);
  if (!m) return null;
  const n = m.slice(1, 12).map((v) => (v === undefined ? undefined : Number(v)));
  if (n.some((v) => v !== undefined && v > 0xffffffff) || n[1]! > 0xffff || n[2] === 0) return null;
  const d: DoseReport = {
    kind: 'dose', stop: n[0]!, program: n[1]!, exposure: n[2]!, onUs: n.slice(3, 7) as number[], cut: m[12] !== undefined, again: m[13] !== undefined,
  };
  if (m[8] !== undefined) d.planUs = n.slice(7, 11) as number[];
  return d;
}

function milli3(ms: string[]): Xyz {
  return [parseMilli(ms[0])!, parseMilli(ms[1])!, parseMilli(ms[2])!];
}

/** Parses one line from the Mega; null when a known prefix carries a malformed payload. */
export function parseReply(line: string): Reply | null {
  if (line === 'ok' || line.startsWith('ok ')) {
    // Flow-control fields count only with an intact checksum (protocol/mega.md §2).
    const m = /^(ok(?: N([0-9]{1,10}))? P([0-9]{1,5}) B([0-9]{1,5}))\*([0-9a-f]{4})$/.exec(line);
    if (!m || m[5] !== crc16Hex(m[1])) return { kind: 'ok' };
    const ok: Reply = { kind: 'ok', p: Number(m[3]), b: Number(m[4]) };
    if (m[2] !== undefined) ok.n = Number(m[2]);
    return ok;
  }
  if (line.startsWith('Error:')) {
    const m = /^Error:E([0-9]{1,4}) (.*)$/.exec(line);
    return m ? { kind: 'error', code: Number(m[1]), message: m[2] } : { kind: 'error', code: 0, message: line.slice(6) };
  }
  if (line.startsWith('Resend:') || line.startsWith('rs ')) {
    const m = /^(?:Resend: ?|rs )([0-9]{1,10})$/.exec(line);
    return m ? { kind: 'resend', n: Number(m[1]) } : null;
  }
  if (line.startsWith('T:')) return parseTemps(line);
  if (line.startsWith('X:')) {
    const m = POSITION.exec(line);
    if (!m) return null;
    return { kind: 'position', um: milli3([m[1], m[2], m[3]]), steps: [Number(m[5]), Number(m[6]), Number(m[7])] };
  }
  if (line.startsWith('Bed X:')) {
    const m = BED.exec(line);
    return m ? { kind: 'probePoint', um: milli3([m[1], m[2], m[3]]) } : null;
  }
  if (line.startsWith('DOSE:')) return parseDose(line);
  if (line.startsWith('JOB:')) {
    const m = /^JOB:([a-z]+)(.*)$/.exec(line);
    const fields = m && JOB_STATES.has(m[1]) ? parseFields(m[2]) : null;
    return fields ? { kind: 'job', state: m![1] as JobState, fields } : null;
  }
  if (line.startsWith('PROBE:')) {
    const s = line.slice(6);
    return PROBE_STATES.has(s) ? { kind: 'probe', state: s as ProbeState } : null;
  }
  if (line.startsWith('TEST:')) {
    const m = /^TEST:(quick|full)(.*)$/.exec(line);
    const fields = m ? parseFields(m[2]) : null;
    return fields ? { kind: 'test', mode: m![1] as 'quick' | 'full', fields } : null;
  }
  if (line.startsWith('FAULT:')) {
    const m = /^FAULT:E([0-9]{1,4}) (.*)$/.exec(line);
    return m ? { kind: 'fault', code: Number(m[1]), message: m[2] } : null;
  }
  if (line.startsWith('echo:')) {
    // A refusal, answered as Marlin answers one (mega.md §2): still this command's error to the app.
    const m = /^echo:E([0-9]{1,4}) (.*)$/.exec(line);
    return m ? { kind: 'error', code: Number(m[1]), message: m[2] } : { kind: 'echo', text: line.slice(5) };
  }
  if (line.startsWith('busy:')) return { kind: 'busy' };
  if (line === 'start') return { kind: 'start' };
  if (line.startsWith('FIRMWARE_NAME:')) {
    const m = /^FIRMWARE_NAME:(.+?) PROTOCOL_VERSION:([0-9]{1,5})(?: |$)/.exec(line);
    return m ? { kind: 'firmware', name: m[1], protocol: Number(m[2]) } : null;
  }
  if (line.startsWith('Cap:')) {
    const m = /^Cap:([A-Z0-9_]+):([0-9]{1,10})$/.exec(line);
    return m ? { kind: 'cap', name: m[1], value: Number(m[2]) } : null;
  }
  return { kind: 'other', text: line };
}
