// Line framing of the Mega dialect: `N<n> <body>*<cs>` or a plain body (protocol/mega.md §1).

import { isPrintable } from './printable';
import { crc16Hex } from './crc16';
import type { SplitLine } from './line-splitter';

export const DIALECT_MAX_LINE = 96;
/** The last line number: one short of int32's end, as the Mega's, so `Resend: <last + 1>` always names a number (mega.md §1). */
export const MAX_LINE_NUMBER = 2147483646;

export type Frame =
  | { ok: true; n?: number; body: string }
  | { ok: false; error: number; n?: number; numbered: boolean };

export function xorChecksum(text: string): number {
  let x = 0;
  for (let i = 0; i < text.length; i++) x ^= text.charCodeAt(i) & 0xff;
  return x;
}

/** `N<n> <body>*<cs>#<crc>` without a newline; `marlin` leaves out the CRC, as Marlin hosts do. */
export function encodeFrame(n: number, body: string, marlin = false): string {
  const head = `N${n} ${body}`;
  return marlin ? `${head}*${xorChecksum(head)}` : `${head}*${xorChecksum(head)}#${crc16Hex(head)}`;
}

function stripComment(s: string): string {
  const i = s.indexOf(';');
  return (i < 0 ? s : s.slice(0, i)).trim();
}

/** The line number a damaged numbered line claims, when its prefix is intact. */
function claimedNumber(text: string): number | undefined {
  const m = /^N(-1|[0-9]{1,10}) /.exec(text);
  if (!m) return undefined;
  const n = Number(m[1]);
  return n <= MAX_LINE_NUMBER ? n : undefined;
}

export function parseFrame(line: SplitLine): Frame {
  const { text } = line;
  const numbered = text.startsWith('N');
  const fail = (error: number): Frame => {
    const n = numbered ? claimedNumber(text) : undefined;
    return n === undefined ? { ok: false, error, numbered } : { ok: false, error, n, numbered };
  };
  if (line.overflow) return fail(5);
  if (!isPrintable(text)) return fail(1);
  if (!numbered) {
    const body = stripComment(text);
    return body.includes('*') ? fail(4) : { ok: true, body };
  }
  const star = text.lastIndexOf('*');
  if (star < 0) return fail(claimedNumber(text) === undefined ? 2 : 3);
  const head = text.slice(0, star);
  const m = /^N(-1|[0-9]{1,10}) +(.*)$/.exec(head);
  const check = /^([0-9]{1,3})(?:#([0-9a-f]{4}))?$/.exec(text.slice(star + 1));
  if (!m || !check || Number(check[1]) !== xorChecksum(head)) return fail(2);
  if (check[2] !== undefined && check[2] !== crc16Hex(head)) return fail(2);
  const n = Number(m[1]);
  if (n > MAX_LINE_NUMBER) return fail(2);
  return { ok: true, n, body: stripComment(m[2]) };
}
