// Run-length rows of job format 2 (protocol/job.md "Run-length rows"): the canonical `rl` records of a row, and the parse of one.

import { JOB_LIMITS } from './job-types';

const HEX = Array.from({ length: 256 }, (_, i) => i.toString(16).padStart(2, '0'));

/** A token of an `rl` record: `n` cells of one value, or literal cells. */
type Token = { col: number; run: number; value: number } | { col: number; end: number };

/** Maximal runs of equal cells from the row's first to its last non-zero cell; runs of `minRun` or more are run tokens. */
function tokens(row: ArrayLike<number>): Token[] {
  let first = 0;
  let last = row.length - 1;
  while (first < row.length && row[first] === 0) first++;
  while (last >= first && row[last] === 0) last--;
  const out: Token[] = [];
  let literal: { col: number; end: number } | null = null;
  for (let c = first; c <= last; ) {
    let end = c + 1;
    while (end <= last && row[end] === row[c]) end++;
    if (end - c >= JOB_LIMITS.minRun) {
      literal = null;
      out.push({ col: c, run: end - c, value: row[c] });
    } else {
      if (!literal) out.push((literal = { col: c, end }));
      literal.end = end;
    }
    c = end;
  }
  return out;
}

const isZeroRun = (t: Token | undefined) => !!t && 'run' in t && t.value === 0;

/** The canonical `rl` records of row `r`, filled greedily to at most 76 bytes each (job.md). */
export function runRecords(r: number, row: ArrayLike<number>): string[] {
  const tokenText = (t: Token) => {
    if ('run' in t) return `${t.run}x${HEX[t.value]}`;
    let s = '';
    for (let c = t.col; c < t.end; c++) s += HEX[row[c]];
    return s;
  };
  const out: string[] = [];
  let parts: Token[] = [];
  let text = '';
  const close = () => {
    while (isZeroRun(parts[parts.length - 1])) parts.pop(); // a record never ends in zeros
    if (parts.length) out.push(`rl ${r} ${parts[0].col} ${parts.map(tokenText).join(' ')}`);
    parts = [];
    text = '';
  };
  for (let t of tokens(row)) {
    for (;;) {
      if (!parts.length) {
        if (isZeroRun(t)) break; // nor starts with them
        text = `rl ${r} ${t.col}`;
      }
      const length = 'run' in t ? `${t.run}`.length + 3 : 2 * (t.end - t.col);
      if (text.length + 1 + length <= JOB_LIMITS.maxRecordBytes) {
        parts.push(t);
        text += ' ' + tokenText(t);
        break;
      }
      const room = Math.floor((JOB_LIMITS.maxRecordBytes - text.length - 1) / 2);
      if ('end' in t && room >= 1) {
        parts.push({ col: t.col, end: t.col + room });
        t = { col: t.col + room, end: t.end };
      }
      close();
    }
  }
  close();
  return out;
}

/**
 * Parses the tokens of an `rl` record after its row and column: the cell count, or null when malformed
 * (a token neither 1+ pairs of lower-case hex digits nor `<n>x<hh>` with n in minRun…maxSide).
 * `emit` gets each token's cells as a run (value, count) or a literal.
 */
export function parseRunTokens(words: string[], emit?: (offset: number, value: number, count: number) => void): number | null {
  if (!words.length) return null;
  let n = 0;
  for (const w of words) {
    const x = w.indexOf('x');
    if (x < 0) {
      if (!/^(?:[0-9a-f]{2})+$/.test(w)) return null;
      for (let i = 0; i < w.length; i += 2) emit?.(n + i / 2, parseInt(w.substr(i, 2), 16), 1);
      n += w.length / 2;
    } else {
      const count = w.slice(0, x);
      const hex = w.slice(x + 1);
      if (!/^[1-9][0-9]{0,3}$/.test(count) || !/^[0-9a-f]{2}$/.test(hex)) return null;
      const k = Number(count);
      if (k < JOB_LIMITS.minRun || k > JOB_LIMITS.maxSide) return null;
      emit?.(n, parseInt(hex, 16), k);
      n += k;
    }
  }
  return n;
}
