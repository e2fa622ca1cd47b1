// The canonical line of each reply and report of the Mega dialect (Mega side): what the firmware
// prints, and what the console shows for a reply it did not see as a line. Parsed by dialect-reply.ts.

import { formatMilli } from './dialect-number';
import { crc16Hex } from './crc16';
import type { Reply } from './dialect-reply';
import { errorClass } from './errors';
import { formatDeciC } from './nano';

/** The end of a reply block: `n` is the line it answers, undefined when it accepts none (mega.md §2). */
export function formatOk(n: number | undefined, p: number, b: number): string {
  const head = n === undefined ? `ok P${p} B${b}` : `ok N${n} P${p} B${b}`;
  return `${head}*${crc16Hex(head)}`;
}

function formatFields(fields: Record<string, string>): string {
  return Object.entries(fields).map(([k, v]) => ` ${k}=${v}`).join('');
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
    case 'dose': {
      const plan = r.planUs ? ` plan=${r.planUs.join(',')}` : '';
      return `DOSE:stop=${r.stop} prog=${r.program} exp=${r.exposure} on=${r.onUs.join(',')}${plan}${r.cut ? ' cut=1' : ''}${r.again ? ' again=1' : ''}`;
    }
  }
}
