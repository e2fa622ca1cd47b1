// Test-only: real picture files written byte by byte, with the resolution their headers state:
// PNG with or without pHYs, baseline JPEG with a JFIF density or an EXIF resolution, BMP with
// pixels per metre. Node only (zlib); the unit tests and the Playwright specs import them.

import { crc32, deflateSync } from 'node:zlib';

/** A pixel's grey, 0 black … 255 white. A JPEG takes one grey per 8 × 8 block, read at its corner. */
export type Shade = (x: number, y: number) => number;

/** Left half black, right half white: line art. */
export const halfBlack = (width: number): Shade => (x) => (x < width / 2 ? 0 : 255);

const u16be = (v: number) => [(v >> 8) & 255, v & 255];
const u32be = (v: number) => [(v >>> 24) & 255, (v >> 16) & 255, (v >> 8) & 255, v & 255];

function pngChunk(type: string, data: Uint8Array): Uint8Array {
  const body = new Uint8Array([...Buffer.from(type, 'latin1'), ...data]);
  return new Uint8Array([...u32be(data.length), ...body, ...u32be(crc32(body))]);
}

/** A greyscale PNG; `pixelsPerMetre` writes a pHYs chunk in metres, `aspectOnly` one with no unit. */
export function pngFile(width: number, height: number, shade: Shade, opts: { pixelsPerMetre?: { x: number; y: number }; aspectOnly?: boolean } = {}): Uint8Array {
  const rows = new Uint8Array((width + 1) * height);
  for (let y = 0; y < height; y++) for (let x = 0; x < width; x++) rows[y * (width + 1) + 1 + x] = shade(x, y);
  const chunks = [pngChunk('IHDR', new Uint8Array([...u32be(width), ...u32be(height), 8, 0, 0, 0, 0]))];
  if (opts.pixelsPerMetre) chunks.push(pngChunk('pHYs', new Uint8Array([...u32be(opts.pixelsPerMetre.x), ...u32be(opts.pixelsPerMetre.y), opts.aspectOnly ? 0 : 1])));
  chunks.push(pngChunk('IDAT', deflateSync(rows)), pngChunk('IEND', new Uint8Array()));
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), ...chunks]);
}

/** A 24-bit BMP, bottom-up; `pixelsPerMetre` 0 states no resolution. */
export function bmpFile(width: number, height: number, shade: Shade, pixelsPerMetre = { x: 0, y: 0 }): Uint8Array {
  const row = Math.ceil((width * 3) / 4) * 4;
  const b = Buffer.alloc(54 + row * height);
  b.write('BM', 0);
  b.writeUInt32LE(b.length, 2);
  b.writeUInt32LE(54, 10);
  b.writeUInt32LE(40, 14);
  b.writeInt32LE(width, 18);
  b.writeInt32LE(height, 22);
  b.writeUInt16LE(1, 26);
  b.writeUInt16LE(24, 28);
  b.writeUInt32LE(row * height, 34);
  b.writeInt32LE(pixelsPerMetre.x, 38);
  b.writeInt32LE(pixelsPerMetre.y, 42);
  for (let y = 0; y < height; y++)
    for (let x = 0; x < width; x++) b.fill(shade(x, height - 1 - y), 54 + y * row + x * 3, 54 + y * row + x * 3 + 3);
  return b;
}

/** JFIF's density: units 0 (an aspect only), 1 (per inch) or 2 (per cm). */
export interface JfifDensity {
  units: 0 | 1 | 2;
  x: number;
  y: number;
}

/** EXIF's resolution in IFD0: unit 1 (none), 2 (inch) or 3 (cm); rationals num/den; either byte order. */
export interface ExifResolution {
  unit: 1 | 2 | 3;
  x: [number, number];
  y: [number, number];
  littleEndian?: boolean;
}

function segment(marker: number, body: number[]): number[] {
  return [0xff, marker, ...u16be(body.length + 2), ...body];
}

function exifBody(e: ExifResolution): number[] {
  const le = e.littleEndian ?? false;
  const u16 = (v: number) => (le ? u16be(v).reverse() : u16be(v));
  const u32 = (v: number) => (le ? u32be(v).reverse() : u32be(v));
  // IFD0 at 8: three entries (12 bytes each), then the next IFD's offset, then the two rationals.
  const data = 8 + 2 + 3 * 12 + 4;
  const tiff = [...(le ? [0x49, 0x49] : [0x4d, 0x4d]), ...u16(42), ...u32(8), ...u16(3),
    ...u16(0x011a), ...u16(5), ...u32(1), ...u32(data),
    ...u16(0x011b), ...u16(5), ...u32(1), ...u32(data + 8),
    ...u16(0x0128), ...u16(3), ...u32(1), ...u16(e.unit), 0, 0,
    ...u32(0), ...u32(e.x[0]), ...u32(e.x[1]), ...u32(e.y[0]), ...u32(e.y[1])];
  return [...Buffer.from('Exif\0\0', 'latin1'), ...tiff];
}

/**
 * A baseline greyscale JPEG whose every 8 × 8 block is flat: each block codes only its DC term
 * (quantised by 1, so a block decodes to exactly its grey), then end-of-block.
 */
export function jpegFile(width: number, height: number, shade: Shade, opts: { jfif?: JfifDensity; exif?: ExifResolution } = {}): Uint8Array {
  const out: number[] = [0xff, 0xd8];
  if (opts.jfif) out.push(...segment(0xe0, [...Buffer.from('JFIF\0', 'latin1'), 1, 1, opts.jfif.units, ...u16be(opts.jfif.x), ...u16be(opts.jfif.y), 0, 0]));
  if (opts.exif) out.push(...segment(0xe1, exifBody(opts.exif)));
  out.push(...segment(0xdb, [0, ...new Array(64).fill(1)]));
  out.push(...segment(0xc0, [8, ...u16be(height), ...u16be(width), 1, 1, 0x11, 0]));
  // DC: the standard luminance table. AC: end-of-block as "0", and a spare symbol as "10".
  const dcBits = [0, 1, 5, 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0];
  out.push(...segment(0xc4, [0x00, ...dcBits, ...Array.from({ length: 12 }, (_, i) => i)]));
  out.push(...segment(0xc4, [0x10, 1, 1, ...new Array(14).fill(0), 0x00, 0x01]));
  out.push(...segment(0xda, [1, 1, 0x00, 0, 63, 0]));
  const dcCode: [number, number][] = [[0b00, 2], [0b010, 3], [0b011, 3], [0b100, 3], [0b101, 3], [0b110, 3], [0b1110, 4], [0b11110, 5], [0b111110, 6], [0b1111110, 7], [0b11111110, 8], [0b111111110, 9]];
  let acc = 0, bits = 0;
  const put = (value: number, length: number) => {
    for (let i = length - 1; i >= 0; i--) {
      acc = (acc << 1) | ((value >> i) & 1);
      if (++bits === 8) {
        out.push(acc);
        if (acc === 0xff) out.push(0); // byte stuffing
        acc = bits = 0;
      }
    }
  };
  let previous = 0;
  for (let by = 0; by < Math.ceil(height / 8); by++)
    for (let bx = 0; bx < Math.ceil(width / 8); bx++) {
      const dc = 8 * (shade(bx * 8, by * 8) - 128);
      const diff = dc - previous;
      previous = dc;
      const size = diff === 0 ? 0 : Math.floor(Math.log2(Math.abs(diff))) + 1;
      put(...dcCode[size]);
      if (size) put(diff > 0 ? diff : diff + (1 << size) - 1, size);
      put(0, 1); // end of block
    }
  if (bits) put((1 << (8 - bits)) - 1, 8 - bits);
  out.push(0xff, 0xd9);
  return new Uint8Array(out);
}
