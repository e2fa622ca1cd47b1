// The Mega dialect's vectors (protocol/vectors/mega.json) as far as the app writes and reads them:
// it writes frames and reads replies. The Mega parses frames and commands and takes lines in its
// C++, checked on every section by firmware/common/protocol/test/dialect_test.cpp.
import { describe, expect, it } from 'vitest';
import { DIALECT_MAX_LINE, encodeFrame } from './dialect-frame';
import { formatMilli } from './dialect-number';
import { parseReply } from './dialect-reply';
import { formatReply } from './reply-format';
import { cases, loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('mega.json');
const count = vectorCounter('mega.json');

describe('mega dialect vectors', () => {
  it('agrees on limits', () => {
    expect(DIALECT_MAX_LINE).toBe(v.maxLine);
    count();
  });

  it.each(cases(v.frames.filter((c: any) => c.canonical), 'line'))('canonical frame %j is what the app writes', (_l, c: any) => {
    expect(c.frame.n === undefined ? c.frame.body : encodeFrame(c.frame.n, c.frame.body)).toBe(c.line);
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
