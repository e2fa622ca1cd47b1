import { describe, expect, it } from 'vitest';
import { formatMilli, parseCommand } from './dialect-command';
import { DIALECT_MAX_LINE, encodeFrame, parseFrame } from './dialect-frame';
import { parseReply } from './dialect-reply';
import { formatReply } from './reply-format';
import { LineSplitter } from './line-splitter';
import { cases, loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('mega.json');
const count = vectorCounter('mega.json');

function split(line: string) {
  const out = new LineSplitter(DIALECT_MAX_LINE).push(line + '\n');
  expect(out).toHaveLength(1);
  return out[0];
}

describe('mega dialect vectors', () => {
  it('agrees on limits', () => {
    expect(DIALECT_MAX_LINE).toBe(v.maxLine);
    count();
  });

  it.each(cases(v.frames, 'line'))('frame %j', (_l, c: any) => {
    expect(parseFrame(split(c.line))).toEqual({ ok: true, ...c.frame });
    if (c.canonical) expect(c.frame.n === undefined ? c.frame.body : encodeFrame(c.frame.n, c.frame.body)).toBe(c.line);
    count();
  });

  it.each(cases(v.frameErrors, 'line'))('frame error %j', (_l, c: any) => {
    const f = parseFrame(split(c.line));
    expect(f.ok).toBe(false);
    if (!f.ok) {
      expect(f.error).toBe(c.error);
      expect(f.n).toBe(c.n);
    }
    count();
  });

  it.each(cases(v.commands, 'body'))('command %j', (_b, c: any) => {
    const r = parseCommand(c.body);
    if (c.error) expect(r).toEqual({ ok: false, error: c.error });
    else expect(r).toEqual({ ok: true, command: c.command });
    count();
  });

  it.each(cases(v.replies, 'line'))('reply %j', (_l, c: any) => {
    expect(parseReply(c.line)).toEqual(c.reply);
    if (c.canonical) expect(formatReply(c.reply)).toBe(c.line);
    count();
  });

  it.each(cases(v.badReplies, 'why'))('bad report (%s) is rejected', (_w, c: any) => {
    expect(parseReply(c.line)).toBeNull();
    count();
  });

  it('formats millimetres with three decimals', () => {
    expect([0, 1, -1, 12345, -2000000000].map(formatMilli)).toEqual(['0.000', '0.001', '-0.001', '12.345', '-2000000.000']);
  });
});

describe('CRC-16/CCITT-FALSE', () => {
  it('gives the standard check value', async () => {
    const { crc16 } = await import('./crc16');
    expect(crc16('123456789')).toBe(0x29b1);
  });
});
