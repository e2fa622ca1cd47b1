import { readFileSync, existsSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { HexError, parseIntelHex, toIntelHex } from './intel-hex';

function record(type: number, offset: number, data: number[]): string {
  const b = [data.length, offset >> 8, offset & 0xff, type, ...data];
  b.push((0x100 - (b.reduce((x, y) => x + y, 0) & 0xff)) & 0xff);
  return ':' + b.map((x) => x.toString(16).padStart(2, '0').toUpperCase()).join('');
}

describe('Intel HEX', () => {
  it('lays records out from address 0 with gaps erased, across 64 KB segments', () => {
    const text = [':03000200000102F8', ':020000040001F9', ':01000000AA55', ':00000001FF'].join('\r\n');
    // the second data record is at 0x10000: extended linear address 1
    const { bytes } = parseIntelHex(text);
    expect(bytes.length).toBe(0x10001);
    expect(Array.from(bytes.subarray(0, 6))).toEqual([0xff, 0xff, 0x00, 0x01, 0x02, 0xff]);
    expect(bytes[0x10000]).toBe(0xaa);
  });

  it('reads back what it writes', () => {
    const bytes = Uint8Array.from({ length: 70000 }, (_, i) => (i * 7) & 0xff);
    expect(parseIntelHex(toIntelHex(bytes)).bytes).toEqual(bytes);
  });

  it.each([
    ['a damaged byte', ':03000200000103F8\n:00000001FF', /line 1 fails its checksum/],
    ['a short record', ':0300020001F0\n:00000001FF', /line 1 holds 1 bytes but says 3/],
    ['no end record', ':03000200000102F8\n', /cut short/],
    ['text that is not HEX', 'hello\n', /line 1 is not an Intel HEX record/],
    ['no data', ':00000001FF', /holds no data/],
  ])('refuses %s', (_, text, message) => {
    expect(() => parseIntelHex(text)).toThrow(HexError);
    expect(() => parseIntelHex(text)).toThrow(message);
  });

  it('refuses data past the largest flash before laying anything out', () => {
    // Extended linear address 0xFFFF, then a byte at 0xFFFF0000: 4 GiB if laid out first.
    const text = [':02000004FFFFFC', ':0100000055AA', ':00000001FF'].join('\n');
    const t0 = performance.now();
    expect(() => parseIntelHex(text)).toThrow(/line 2 puts data at 0xFFFF0000, past the 256 KB of flash/);
    expect(performance.now() - t0).toBeLessThan(100);
    // The limit is the caller's: the Nano's flash refuses what the Mega's would take.
    expect(() => parseIntelHex([':020000040001F9', ':0100000055AA', ':00000001FF'].join('\n'), 32768)).toThrow(/0x10000, past the 32 KB/);
    // The Mega's last byte below 256 KB is taken.
    expect(parseIntelHex([record(4, 0, [0x00, 0x03]), record(0, 0xfff0, Array(16).fill(1)), ':00000001FF'].join('\n')).bytes.length).toBe(0x40000);
  });

  it.runIf(existsSync('build/avr/nano.hex'))('reads the Nano image the build makes', () => {
    const { bytes } = parseIntelHex(readFileSync('build/avr/nano.hex', 'utf8'));
    expect(bytes.length).toBeGreaterThan(1000);
    expect([bytes[0], bytes[1]]).toEqual([0x0c, 0x94]); // jmp: the reset vector
  });
});
