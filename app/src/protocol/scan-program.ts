// Scan programs on the printhead link (protocol/nano.md "Scan programs"): a pass's per-LED light
// merged into events, the events cut into a chain of programs and their B (packed) and K lines, and
// the check. The C++ twin is firmware/common/protocol/src/scan_program.*.

import { NANO_MAX_LINE } from './nano';

export const PROGRAM_EVENTS = 64;
export const PROGRAM_MAX_DELTA = 2 ** 28 - 1;
/** A chain's time 0 is this long after the `\n` of its `G` arrives. */
export const PROGRAM_START_LEAD_US = 1000;
/** A running chain that hears no line for longer than this is cut (the Mega, and so the head, stopped). */
export const CHAIN_SILENCE_US = 50_000;
export const SEAL_CONTINUATION = 1;
export const SEAL_MORE = 2;

/** An event: from `t` µs after time 0 the LEDs are in state `m` (bit k = LED k). */
export type ScanEvent = [t: number, m: number];

/** The check: CRC-16/CCITT-FALSE over each event's word d × 16 + m, 4 bytes little-endian. */
export function checkEvents(rel: [d: number, m: number][]): number {
  let c = 0xffff;
  for (const [d, m] of rel) {
    let w = d * 16 + m;
    for (let b = 0; b < 4; b++) {
      c ^= (w % 256) << 8;
      w = Math.floor(w / 256);
      for (let k = 0; k < 8; k++) c = c & 0x8000 ? ((c << 1) ^ 0x1021) & 0xffff : (c << 1) & 0xffff;
    }
  }
  return c;
}

/** Merges per-LED [on, off] µs lists (each in time order) into one event per switching time. */
export function mergeLight(leds: [number, number][][]): ScanEvent[] {
  const edges = new Map<number, number>(); // time → bits toggled
  leds.forEach((intervals, k) => {
    for (const [on, off] of intervals) {
      edges.set(on, (edges.get(on) ?? 0) ^ (1 << k));
      edges.set(off, (edges.get(off) ?? 0) ^ (1 << k));
    }
  });
  const out: ScanEvent[] = [];
  let state = 0;
  for (const t of [...edges.keys()].sort((a, b) => a - b)) {
    const toggled = edges.get(t)!;
    if (!toggled) continue; // an interval ending where the LED's next begins: it stays on
    state ^= toggled;
    out.push([t, state]);
  }
  return out;
}

/** A B line's packing of an event word d × 16 + m: 5 bits a character, most significant first, each '?' + the bits, + 32 on all but the last. */
export const PACK_BASE = 0x3f;
const PACK_MORE = 32;

export function packWord(w: number): string {
  const groups: number[] = [];
  do {
    groups.unshift(w % 32);
    w = Math.floor(w / 32);
  } while (w > 0);
  return groups.map((g, i) => String.fromCharCode(PACK_BASE + g + (i < groups.length - 1 ? PACK_MORE : 0))).join('');
}

/** The chain's lines as the Mega sends them, without terminators: each program's B lines, then its K line. */
export function programLines(events: ScanEvent[]): string[] {
  if (events.length === 0) throw new RangeError('a program needs at least one event');
  const lines: string[] = [];
  let prev: number | null = null;
  for (let start = 0; start < events.length; start += PROGRAM_EVENTS) {
    const rel: [number, number][] = [];
    for (const [t, m] of events.slice(start, start + PROGRAM_EVENTS)) {
      const d = prev === null ? t : t - prev;
      if (!Number.isInteger(t) || !(m >= 0 && m <= 15) || d > PROGRAM_MAX_DELTA || (prev !== null && d < 1) || d < 0) {
        throw new RangeError(`event [${t}, ${m}] cannot follow ${prev}`);
      }
      rel.push([d, m]);
      prev = t;
    }
    let seq = 0;
    let cur: string | null = null;
    for (const [d, m] of rel) {
      const word = packWord(d * 16 + m);
      if (cur !== null && cur.length + word.length > NANO_MAX_LINE) {
        lines.push(cur);
        cur = null;
      }
      cur ??= `B:${seq++},`;
      cur += word;
    }
    lines.push(cur!);
    const flags = (start > 0 ? SEAL_CONTINUATION : 0) | (start + PROGRAM_EVENTS < events.length ? SEAL_MORE : 0);
    lines.push(`K:${flags},${rel.length},${checkEvents(rel)}`);
  }
  return lines;
}

/** An `A:q,d,m…` line's number and events, or null when malformed. */
export function parseAppend(line: string): { seq: number; events: [number, number][] } | null {
  const m = /^A:([0-9]{1,5})((?:,[0-9]{1,9},[0-9]{1,2})+)$/.exec(line);
  if (!m || Number(m[1]) > 65535) return null;
  const nums = m[2].slice(1).split(',').map(Number);
  const events: [number, number][] = [];
  for (let i = 0; i < nums.length; i += 2) {
    if (nums[i] > PROGRAM_MAX_DELTA || nums[i + 1] > 15) return null;
    events.push([nums[i], nums[i + 1]]);
  }
  return { seq: Number(m[1]), events };
}

/** A `B:q,<packed>` line's number and events, or null when malformed (nano.md: no leading zero bits, each word below 2³²). */
export function parsePacked(line: string): { seq: number; events: [number, number][] } | null {
  const m = /^B:([0-9]{1,5}),([?-~]+)$/.exec(line);
  if (!m || Number(m[1]) > 65535) return null;
  const events: [number, number][] = [];
  let w = 0, first = true;
  for (const ch of m[2]) {
    const v = ch.charCodeAt(0) - PACK_BASE;
    if ((first && v === PACK_MORE) || w >= 2 ** 27) return null;
    w = w * 32 + (v % 32);
    first = v < PACK_MORE;
    if (first) {
      events.push([Math.floor(w / 16), w % 16]);
      w = 0;
    }
  }
  return first ? { seq: Number(m[1]), events } : null;
}

/** A `K:f,n,c` line's fields, or null when malformed. */
export function parseSeal(line: string): { flags: number; events: number; check: number } | null {
  const m = /^K:([0-3]),([0-9]{1,2}),([0-9]{1,5})$/.exec(line);
  if (!m) return null;
  const [flags, events, check] = [Number(m[1]), Number(m[2]), Number(m[3])];
  return events >= 1 && events <= PROGRAM_EVENTS && check <= 0xffff ? { flags, events, check } : null;
}
