// Line framing of the Mega dialect: `N<n> <body>*<cs>` or a plain body (protocol/mega.md §1).

import { isPrintable } from './bytes';
import type { SplitLine } from './line-splitter';

export const DIALECT_MAX_LINE = 96;
export const MAX_LINE_NUMBER = 2147483647;

export type Frame =
  | { ok: true; n?: number; body: string }
  | { ok: false; error: number; n?: number; numbered: boolean };

export function xorChecksum(text: string): number {
  let x = 0;
  for (let i = 0; i < text.length; i++) x ^= text.charCodeAt(i) & 0xff;
  return x;
}

/** `N<n> <body>*<cs>` without a newline. */
export function encodeFrame(n: number, body: string): string {
  const head = `N${n} ${body}`;
  return `${head}*${xorChecksum(head)}`;
}

function stripComment(s: string): string {
  const i = s.indexOf(';');
  return (i < 0 ? s : s.slice(0, i)).trim();
}

/** The line number a damaged numbered line claims, when its prefix is intact. */
function claimedNumber(text: string): number | undefined {
  const m = /^N([0-9]{1,10}) /.exec(text);
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
  const m = /^N([0-9]{1,10}) +(.*)$/.exec(text.slice(0, star));
  const cs = text.slice(star + 1);
  if (!m || !/^[0-9]{1,3}$/.test(cs) || Number(cs) !== xorChecksum(text.slice(0, star))) return fail(2);
  const n = Number(m[1]);
  if (n > MAX_LINE_NUMBER) return fail(2);
  return { ok: true, n, body: stripComment(m[2]) };
}
