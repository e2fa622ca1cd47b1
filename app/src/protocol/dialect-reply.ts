// Replies and reports of the Mega dialect: typed parse (host side) and canonical format (Mega side).

import { formatMilli, parseMilli } from './dialect-command';
import { crc16Hex } from './crc16';
import { errorClass } from './errors';
import { formatDeciC, parseDeciC, SENSOR_COUNT } from './nano';

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
  | { kind: 'other'; text: string };

const JOB_STATES = new Set(['idle', 'uploading', 'ready', 'running', 'paused', 'done', 'aborted', 'failed', 'interrupted']);
const PROBE_STATES = new Set(['triggered', 'open', 'alarm', 'deployed', 'stowed']);
const MM = '(-?[0-9]{1,7}\\.[0-9]{3})';
const POSITION = new RegExp(`^X:${MM} Y:${MM} Z:${MM} E:${MM} Count X:(-?[0-9]{1,10}) Y:(-?[0-9]{1,10}) Z:(-?[0-9]{1,10})$`);
const BED = new RegExp(`^Bed X: ${MM} Y: ${MM} Z: ${MM}$`);
const DECI = '(-?[0-9]{1,3}\\.[0-9])';
const TEMP_PAIR = new RegExp(`^S([0-5]):${DECI} /0\\.0$`);

/** The end of a reply block: `n` is the line it answers, undefined when it accepts none (mega.md §2). */
export function formatOk(n: number | undefined, p: number, b: number): string {
  const head = n === undefined ? `ok P${p} B${b}` : `ok N${n} P${p} B${b}`;
  return `${head}*${crc16Hex(head)}`;
}

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

function formatFields(fields: Record<string, string>): string {
  return Object.entries(fields).map(([k, v]) => ` ${k}=${v}`).join('');
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

export interface FirmwareInfo {
  machine: string;
}

/** Canonical line for a reply; the Mega and the simulated printer print exactly this. */
export function formatReply(r: Reply, info: FirmwareInfo = { machine: 'UV-LED exposure printer' }): string {
  switch (r.kind) {
    case 'ok': return r.p === undefined ? 'ok' : formatOk(r.n, r.p, r.b ?? 0);
    case 'error': return `${errorClass(r.code) === 'refusal' ? 'echo:' : 'Error:'}E${r.code} ${r.message}`;
    case 'resend': return `Resend: ${r.n}`;
    case 'temps': {
      // Hosts read `T:` as a hotend and `Tn:` as more of them, and every `/` value as a heater's target:
      // one `T:` and the sensors as `S0`-`S5` (OctoPrint keeps them as custom sensors), all with target
      // 0.0. The soft limits are config (`M850 thermal.limit.<i>`), never a target a host would show.
      const pairs = r.deciC.map((v, i) => ` S${i}:${formatDeciC(v)} /0.0`).join('');
      return `T:${formatDeciC(Math.max(...r.deciC))} /0.0${pairs}`;
    }
    case 'position': {
      const [x, y, z] = r.um.map(formatMilli);
      return `X:${x} Y:${y} Z:${z} E:0.000 Count X:${r.steps[0]} Y:${r.steps[1]} Z:${r.steps[2]}`;
    }
    case 'probePoint': {
      const [x, y, z] = r.um.map(formatMilli);
      return `Bed X: ${x} Y: ${y} Z: ${z}`;
    }
    case 'job': return `JOB:${r.state}${formatFields(r.fields)}`;
    case 'probe': return `PROBE:${r.state}`;
    case 'test': return `TEST:${r.mode}${formatFields(r.fields)}`;
    case 'fault': return `FAULT:E${r.code} ${r.message}`;
    case 'echo': return `echo:${r.text}`;
    case 'busy': return 'busy: processing';
    case 'start': return 'start';
    case 'firmware':
      return `FIRMWARE_NAME:${r.name} PROTOCOL_VERSION:${r.protocol} MACHINE_TYPE:${info.machine} LEDS:4 SENSORS:6`;
    case 'cap': return `Cap:${r.name}:${r.value}`;
    case 'other': return r.text;
  }
}
