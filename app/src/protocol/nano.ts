// Codec for the Mega <-> Nano printhead link (protocol/nano.md).

import { isPrintable } from './printable';
import type { SplitLine } from './line-splitter';

export const NANO_MAX_LINE = 63;
export const LED_COUNT = 4;
export const SENSOR_COUNT = 6;
/** The events a scan program holds (nano.md "Scan programs"): the Mega cuts a pass's chain into programs of this many. */
export const PROGRAM_EVENTS = 64;

export type NanoCommand =
  | { op: 'S' | 'D' | 'U' | 'X' | 'P' | 'T' | 'R' | 'E' | 'V' | 'C' | 'G' | 'Q' | 'W' | 'O' }
  | { op: 'F'; mask: number; durations: [number, number, number, number] }
  /** Link speed: both sides take `baud` once the Nano's `L` reply has gone out (protocol/nano.md "Link speed"). */
  | { op: 'L'; baud: number };

/** The power-on speed of the printhead link, and the one both sides fall back to. */
export const NANO_BAUD = 115200;
/** The speeds an `L` may ask for: 115200 and the three exact at 16 MHz with U2X. Any other is refused. */
export const NANO_LINK_BAUDS: readonly number[] = [115200, 250000, 500000, 1000000];

export type NanoReply =
  | { op: 'S'; mask: number }
  | { op: 'P'; triggered: boolean }
  | { op: 'T'; deciC: number[] }
  | { op: 'E'; flags: number }
  | { op: 'V'; protocol: number; firmware: string }
  /** The Nano's start count, exposures lit since then, and whether the last one ran its full time. */
  | { op: 'C'; boot: number; fires: number; whole: boolean }
  /** A scan program's seal: 0 armed, else why it was refused (protocol/nano.md "Scan programs"). */
  | { op: 'K'; code: number }
  /** Buffers free to load, programs armed, and what became of the last chain started. */
  | { op: 'Q'; free: number; armed: number; pass: number }
  /** The Nano's micros() when the W's newline arrived: the Mega measures the Nano's clock by it. */
  | { op: 'W'; us: number }
  /** The speed both sides take once this reply has gone out. */
  | { op: 'L'; baud: number }
  /** No dose record waits (protocol/nano.md "Dose records"). */
  | { op: 'O'; exposure: 0 }
  /** A dose record: the exposure's number (as C counts it), the program's place in its chain (0 for an F), each LED's on-time in µs. */
  | { op: 'O'; exposure: number; program: number; onUs: [number, number, number, number] };

export type Colour = 'green' | 'dim_white' | 'purple' | 'cyan' | 'orange' | 'red';

export const NANO_COLOURS: Record<Colour, [number, number, number]> = {
  green: [0, 40, 0],
  dim_white: [24, 24, 24],
  purple: [96, 0, 128],
  cyan: [0, 96, 96],
  orange: [160, 48, 0],
  red: [128, 0, 0],
};

export const FAULT = {
  OVERTEMP: 1,
  SENSOR: 2,
  CAPPED: 4,
  BUSY: 8,
  REFUSED: 16,
  MALFORMED: 32,
  WATCHDOG: 64,
  CUTOFF: 128,
} as const;

const FLASH: Record<NanoCommand['op'], Colour> = {
  S: 'dim_white', T: 'dim_white', E: 'dim_white', V: 'dim_white', C: 'dim_white',
  F: 'purple', D: 'cyan', U: 'cyan', X: 'cyan', P: 'cyan', R: 'orange',
  G: 'purple', Q: 'dim_white', W: 'dim_white', L: 'dim_white', O: 'dim_white',
};

export function flashColour(op: NanoCommand['op']): Colour {
  return FLASH[op];
}

const U32_MAX = 4294967295;

/** Unsigned decimal, 1-10 digits, leading zeros allowed; null if not. */
function parseU32(s: string): number | null {
  if (!/^[0-9]{1,10}$/.test(s)) return null;
  const v = Number(s);
  return v <= U32_MAX ? v : null;
}

/** Whether the Nano treats a split line as a command candidate (not dropped as malformed). */
export function nanoLineUsable(line: SplitLine): boolean {
  return !line.overflow && isPrintable(line.text);
}

/** Parses one line (without terminator). null = malformed: the Nano drops it. */
export function parseNanoCommand(line: string): NanoCommand | null {
  if (line.length === 1 && 'SDUXPTREVCGQWO'.includes(line)) {
    return { op: line as 'S' };
  }
  if (line.startsWith('L:')) {
    // A speed not in the table is malformed: refused, never rounded or wrapped.
    const baud = parseU32(line.slice(2));
    return baud !== null && NANO_LINK_BAUDS.includes(baud) ? { op: 'L', baud } : null;
  }
  if (!line.startsWith('F:')) return null;
  const fields = line.slice(2).split(',');
  if (fields.length !== 5) return null;
  const nums = fields.map(parseU32);
  if (nums.some((n) => n === null)) return null;
  const [mask, d0, d1, d2, d3] = nums as number[];
  if (mask > 15) return null;
  return { op: 'F', mask, durations: [d0, d1, d2, d3] };
}

export function formatNanoCommand(cmd: NanoCommand): string {
  if (cmd.op === 'F') {
    // Out of range is refused, never sent for the Nano to reject (as the C++ codec does).
    const uint32 = (v: number) => Number.isInteger(v) && v >= 0 && v <= 0xffffffff;
    if (!uint32(cmd.mask) || cmd.mask > 15 || !cmd.durations.every(uint32)) throw new RangeError(`F out of range: mask ${cmd.mask}, durations ${cmd.durations.join(',')}`);
    return `F:${cmd.mask},${cmd.durations.join(',')}\n`;
  }
  if (cmd.op === 'L') {
    if (!NANO_LINK_BAUDS.includes(cmd.baud)) throw new RangeError(`L: no such link speed ${cmd.baud}`);
    return `L:${cmd.baud}\n`;
  }
  return `${cmd.op}\n`;
}

/** Formats tenths of a degree as the link's one-decimal Celsius. */
export function formatDeciC(v: number): string {
  const a = Math.abs(v);
  return `${v < 0 ? '-' : ''}${Math.floor(a / 10)}.${a % 10}`;
}

/** Parses `-?d{1,3}.d` into tenths; null if not that shape. */
export function parseDeciC(s: string, maxIntDigits = 3): number | null {
  const m = /^(-?)([0-9]+)\.([0-9])$/.exec(s);
  if (!m || m[2].length > maxIntDigits) return null;
  const v = Number(m[2]) * 10 + Number(m[3]);
  return m[1] ? -v : v;
}

export function formatNanoReply(r: NanoReply): string {
  switch (r.op) {
    case 'S': return `S:${r.mask}\n`;
    case 'P': return `P:${r.triggered ? 1 : 0}\n`;
    case 'T': return `T:${r.deciC.map(formatDeciC).join(',')}\n`;
    case 'E': return `E:${r.flags}\n`;
    case 'V': return `V:${r.protocol},${r.firmware}\n`;
    case 'C': return `C:${r.boot},${r.fires},${r.whole ? 1 : 0}\n`;
    case 'K': return `K:${r.code}\n`;
    case 'Q': return `Q:${r.free},${r.armed},${r.pass}\n`;
    case 'W': return `W:${r.us}\n`;
    case 'L': return `L:${r.baud}\n`;
    case 'O': {
      if (r.exposure === 0) return 'O:0\n';
      const rec = r as Extract<NanoReply, { program: number }>;
      const u32 = (v: number) => Number.isInteger(v) && v >= 0 && v <= U32_MAX;
      // Out of range is refused, never wrapped (as the C++ codec's fields cannot hold it).
      if (!u32(rec.exposure) || !Number.isInteger(rec.program) || rec.program < 0 || rec.program > 65535 || !rec.onUs.every(u32)) {
        throw new RangeError(`O out of range: ${rec.exposure},${rec.program},${rec.onUs.join(',')}`);
      }
      return `O:${rec.exposure},${rec.program},${rec.onUs.join(',')}\n`;
    }
  }
}

/** Parses a reply line (with or without its '\n'); null if malformed. */
export function parseNanoReply(raw: string): NanoReply | null {
  if (!raw.endsWith('\n')) return null;
  const line = raw.slice(0, -1);
  const m = /^([SPTEVCKQWLO]):(.*)$/.exec(line);
  if (!m) return null;
  const body = m[2];
  switch (m[1]) {
    case 'S': {
      const v = /^[0-9]{1,2}$/.test(body) ? Number(body) : -1;
      return v >= 0 && v <= 15 ? { op: 'S', mask: v } : null;
    }
    case 'P':
      return body === '1' || body === '0' ? { op: 'P', triggered: body === '1' } : null;
    case 'T': {
      const parts = body.split(',');
      if (parts.length !== SENSOR_COUNT) return null;
      const vals = parts.map((p) => parseDeciC(p));
      return vals.every((v) => v !== null) ? { op: 'T', deciC: vals as number[] } : null;
    }
    case 'E': {
      const v = /^[0-9]{1,3}$/.test(body) ? Number(body) : -1;
      return v >= 0 && v <= 255 ? { op: 'E', flags: v } : null;
    }
    case 'V': {
      const v = /^([0-9]{1,5}),([0-9A-Za-z.+-]{1,20})$/.exec(body);
      return v ? { op: 'V', protocol: Number(v[1]), firmware: v[2] } : null;
    }
    case 'C': {
      const v = /^([0-9]{1,5}),([0-9]{1,10}),([01])$/.exec(body);
      if (!v || Number(v[1]) > 65535 || Number(v[2]) > U32_MAX) return null;
      return { op: 'C', boot: Number(v[1]), fires: Number(v[2]), whole: v[3] === '1' };
    }
    case 'K':
      return /^[0-7]$/.test(body) ? { op: 'K', code: Number(body) } : null;
    case 'Q': {
      const v = /^([0-2]),([0-2]),([0-7])$/.exec(body);
      return v ? { op: 'Q', free: Number(v[1]), armed: Number(v[2]), pass: Number(v[3]) } : null;
    }
    case 'W': {
      const us = parseU32(body);
      return us === null ? null : { op: 'W', us };
    }
    case 'L': {
      const baud = parseU32(body);
      return baud !== null && NANO_LINK_BAUDS.includes(baud) ? { op: 'L', baud } : null;
    }
    case 'O': {
      const fields = body.split(',');
      const exposure = parseU32(fields[0]);
      if (exposure === 0) return fields.length === 1 ? { op: 'O', exposure: 0 } : null;
      if (exposure === null || fields.length !== 6) return null;
      const program = /^[0-9]{1,5}$/.test(fields[1]) ? Number(fields[1]) : -1;
      const onUs = fields.slice(2).map(parseU32);
      if (program < 0 || program > 65535 || onUs.some((v) => v === null)) return null;
      return { op: 'O', exposure, program, onUs: onUs as [number, number, number, number] };
    }
  }
  return null;
}
