// The resolution a picture file states in its header: PNG's pHYs chunk, JPEG's JFIF density or
// EXIF resolution, BMP's pixels per metre. A file that states none (or only an aspect) gives null:
// the user is asked, never a size guessed.

/** Dots per inch across (x) and down (y). */
export interface Density {
  x: number;
  y: number;
}

const INCH_MM = 25.4;

/** The resolution stated by a PNG, JPEG or BMP file's header; null if it states none or is another kind. */
export function densityOf(bytes: Uint8Array): Density | null {
  if (bytes[0] === 0x89 && bytes[1] === 0x50 && bytes[2] === 0x4e && bytes[3] === 0x47) return pngDensity(bytes);
  if (bytes[0] === 0xff && bytes[1] === 0xd8) return jpegDensity(bytes);
  if (bytes[0] === 0x42 && bytes[1] === 0x4d) return bmpDensity(bytes);
  return null;
}

const view = (b: Uint8Array) => new DataView(b.buffer, b.byteOffset, b.byteLength);

/** A density only if both axes are positive and finite. */
function stated(x: number, y: number): Density | null {
  return x > 0 && y > 0 && Number.isFinite(x) && Number.isFinite(y) ? { x, y } : null;
}

const perMetre = (x: number, y: number) => stated((x * INCH_MM) / 1000, (y * INCH_MM) / 1000);

/** pHYs: pixels per unit X and Y (4 bytes each), then the unit: 1 the metre, 0 an aspect only. */
export function pngDensity(b: Uint8Array): Density | null {
  const v = view(b);
  for (let at = 8; at + 12 <= b.length; ) {
    const length = v.getUint32(at);
    const type = String.fromCharCode(b[at + 4], b[at + 5], b[at + 6], b[at + 7]);
    if (type === 'IDAT' || type === 'IEND') return null; // pHYs must come before the pixels
    if (type === 'pHYs' && length >= 9 && at + 17 <= b.length) return b[at + 16] === 1 ? perMetre(v.getUint32(at + 8), v.getUint32(at + 12)) : null;
    at += 12 + length;
  }
  return null;
}

/** BMP: the info header's pixels per metre, X at byte 38 and Y at 42 (absent from the old 12-byte header). */
export function bmpDensity(b: Uint8Array): Density | null {
  if (b.length < 46) return null;
  const v = view(b);
  if (v.getUint32(14, true) < 40) return null;
  return perMetre(v.getInt32(38, true), v.getInt32(42, true));
}

/**
 * JPEG: JFIF's density (APP0: units 1 per inch, 2 per cm) first, else EXIF's XResolution and
 * YResolution (APP1, in IFD0: unit 2 inch, the default, or 3 cm). Only the segments before the
 * frame are read.
 */
export function jpegDensity(b: Uint8Array): Density | null {
  const v = view(b);
  let exif: Density | null = null;
  for (let at = 2; at + 4 <= b.length; ) {
    if (b[at] !== 0xff) return exif;
    const marker = b[at + 1];
    if (marker === 0xff) {
      at++; // fill byte
      continue;
    }
    if (marker === 0xda || (marker >= 0xc0 && marker <= 0xcf && marker !== 0xc4 && marker !== 0xc8 && marker !== 0xcc)) return exif;
    const length = v.getUint16(at + 2);
    const body = b.subarray(at + 4, Math.min(b.length, at + 2 + length));
    if (marker === 0xe0 && latin1(body, 0, 5) === 'JFIF\0' && body.length >= 12) {
      const units = body[7], x = (body[8] << 8) | body[9], y = (body[10] << 8) | body[11];
      if (units === 1) return stated(x, y);
      if (units === 2) return stated(x * 2.54, y * 2.54);
    } else if (marker === 0xe1 && latin1(body, 0, 6) === 'Exif\0\0') exif ??= exifDensity(body.subarray(6));
    at += 2 + length;
  }
  return exif;
}

function latin1(b: Uint8Array, from: number, n: number): string {
  return String.fromCharCode(...b.subarray(from, from + n));
}

/** A TIFF structure's IFD0: XResolution (0x011a), YResolution (0x011b), ResolutionUnit (0x0128). */
function exifDensity(t: Uint8Array): Density | null {
  if (t.length < 8) return null;
  const le = t[0] === 0x49;
  const v = view(t);
  const u16 = (at: number) => v.getUint16(at, le), u32 = (at: number) => v.getUint32(at, le);
  const ifd = u32(4);
  if (ifd + 2 > t.length) return null;
  let x = 0, y = 0, unit = 2;
  const rational = (entry: number) => {
    const at = u32(entry + 8);
    if (u16(entry + 2) !== 5 || at + 8 > t.length) return 0;
    const den = u32(at + 4);
    return den ? u32(at) / den : 0;
  };
  for (let i = 0, n = u16(ifd); i < n; i++) {
    const e = ifd + 2 + i * 12;
    if (e + 12 > t.length) break;
    const tag = u16(e);
    if (tag === 0x011a) x = rational(e);
    else if (tag === 0x011b) y = rational(e);
    else if (tag === 0x0128) unit = u16(e + 8);
  }
  if (unit === 2) return stated(x, y);
  if (unit === 3) return stated(x * 2.54, y * 2.54);
  return null;
}

/** A picture's size in cells at its density and the machine's pitch: within half a cell of true. */
export function cellsAt(pixels: { width: number; height: number }, dpi: Density, pitchUm: { x: number; y: number }): { w: number; h: number } {
  return {
    w: Math.max(1, Math.round((pixels.width / dpi.x) * INCH_MM * (1000 / pitchUm.x))),
    h: Math.max(1, Math.round((pixels.height / dpi.y) * INCH_MM * (1000 / pitchUm.y))),
  };
}

/**
 * The resolution to show for a picture `pixels` wide over `cells` of `pitchUm`: the roundest one
 * that gives it those cells. Its pixels over its width in inches alone read "600.3 DPI" for a
 * 600-dpi picture, as the width is whole cells (issue 29, item 14).
 */
export function shownDpi(pixels: number, cells: number, pitchUm: number): number {
  const exact = (pixels * INCH_MM * 1000) / (cells * pitchUm);
  for (let digits = 0; digits <= 3; digits++) {
    const d = Number(exact.toFixed(digits));
    if (d > 0 && cellsAt({ width: pixels, height: 1 }, { x: d, y: d }, { x: pitchUm, y: pitchUm }).w === cells) return d;
  }
  return exact;
}
