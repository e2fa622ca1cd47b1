import { createHash } from 'node:crypto';
import { describe, expect, it } from 'vitest';
import { md5Hex } from './md5';

const text = (s: string) => new TextEncoder().encode(s);

describe('MD5', () => {
  it.each([
    ['', 'd41d8cd98f00b204e9800998ecf8427e'],
    ['a', '0cc175b9c0f1b6a831c399e269772661'],
    ['abc', '900150983cd24fb0d6963f7d28e17f72'],
    ['message digest', 'f96b697d7cb7938d525a2f31aaf161d0'],
    ['12345678901234567890123456789012345678901234567890123456789012345678901234567890', '57edf4a22be3c955ac49da2e2107b67a'],
  ])('gives RFC 1321\'s digest of "%s"', (input, digest) => {
    expect(md5Hex(text(input))).toBe(digest);
  });

  it("agrees with Node's at every length around a block's end, and over a megabyte", () => {
    for (let n = 50; n < 140; n++) {
      const data = Uint8Array.from({ length: n }, (_, i) => (i * 7 + n) & 0xff);
      expect(md5Hex(data)).toBe(createHash('md5').update(data).digest('hex'));
    }
    const big = Uint8Array.from({ length: 1 << 20 }, (_, i) => (i * 131) & 0xff);
    expect(md5Hex(big)).toBe(createHash('md5').update(big).digest('hex'));
  });
});

describe('MD5 of a part of a larger buffer', () => {
  it('hashes only the view, not the buffer behind it', () => {
    const bundle = Uint8Array.from({ length: 4096 }, (_, i) => (i * 13) & 0xff);
    const part = bundle.subarray(1000, 3000);
    expect(md5Hex(part)).toBe(createHash('md5').update(part).digest('hex'));
    expect(md5Hex(part)).not.toBe(md5Hex(bundle));
  });
});
