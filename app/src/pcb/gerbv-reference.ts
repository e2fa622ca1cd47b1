// Test support: gerbv's own raster of a file on a given cell grid, its holes, and how far ours agree with them (Node only).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { gunzipSync, inflateSync } from 'node:zlib';
import type { Hole, Slot } from './plot-to-artwork';

/** Debian's copy of gerbv's example boards (package gerbv). */
export const EXAMPLES = '/usr/share/doc/gerbv/examples';

/** An example's text, and a path gerbv can read (Debian may have gzipped it: then a plain copy in `dir`). */
export function gerbvExample(file: string, dir: string): { text: string; path: string } | null {
  const path = join(EXAMPLES, file);
  if (existsSync(path)) return { text: readFileSync(path, 'latin1'), path };
  if (!existsSync(`${path}.gz`)) return null;
  const text = gunzipSync(readFileSync(`${path}.gz`)).toString('latin1');
  const plain = join(dir, file.replace(/\//g, '_'));
  writeFileSync(plain, text, 'latin1');
  return { text, path: plain };
}

/** Every example file, as "folder/name" (a gzipped one without its .gz). */
export function gerbvExampleFiles(): string[] {
  if (!existsSync(EXAMPLES)) return [];
  return readdirSync(EXAMPLES, { withFileTypes: true })
    .filter((d) => d.isDirectory())
    .flatMap((d) => readdirSync(join(EXAMPLES, d.name)).map((f) => `${d.name}/${f.replace(/\.gz$/, '')}`))
    .sort();
}

export interface Grid {
  cols: number;
  rows: number;
  /** Lower left corner of the grid, mm. */
  x0: number;
  y0: number;
  pitchMm: number;
}

/** gerbv is there to ask. */
export function hasGerbv(): boolean {
  try {
    execFileSync('gerbv', ['--version'], { stdio: 'ignore' });
    return true;
  } catch {
    return false;
  }
}

/** gerbv draws at most 2000 pixels a side: larger grids are drawn in tiles of this many. */
const TILE = 2000;

/**
 * gerbv's picture of one file, one cell per pixel: row 0 on top, 1 where it drew. No border, no antialiasing:
 * cairo then lights a pixel whose centre the artwork covers.
 */
export function gerbvCells(path: string, g: Grid): Uint8Array {
  const cells = new Uint8Array(g.cols * g.rows);
  for (let r0 = 0; r0 < g.rows; r0 += TILE) {
    for (let c0 = 0; c0 < g.cols; c0 += TILE) {
      const cols = Math.min(TILE, g.cols - c0);
      const rows = Math.min(TILE, g.rows - r0);
      const tile = gerbvTile(path, { cols, rows, x0: g.x0 + c0 * g.pitchMm, y0: g.y0 + (g.rows - r0 - rows) * g.pitchMm, pitchMm: g.pitchMm });
      for (let r = 0; r < rows; r++) cells.set(tile.subarray(r * cols, (r + 1) * cols), (r0 + r) * g.cols + c0);
    }
  }
  return cells;
}

function gerbvTile(path: string, g: Grid): Uint8Array {
  const dir = mkdtempSync(join(tmpdir(), 'gerbv-'));
  try {
    const png = join(dir, 'layer.png');
    const dpi = 25.4 / g.pitchMm;
    // gerbv reads an origin of at most 20 characters: the caller keeps the grid's corner to a few decimals.
    const origin = `${+g.x0.toFixed(4)}x${+g.y0.toFixed(4)}`;
    if (origin.length > 20) throw new Error(`origin ${origin} is too long for gerbv`);
    // gerbv exits non-zero after a good export on some builds: the file it leaves is what counts.
    try {
      execFileSync('gerbv', ['-u', 'mm', '-x', 'png', '-D', String(+dpi.toFixed(6)), '-B', '0', '-O', origin, '-w', `${g.cols}x${g.rows}`, '-f', '#ffffff', '-b', '#000000', '-o', png, path], { stdio: 'pipe', timeout: 120_000 });
    } catch (e) {
      if (!existsPng(png)) throw e;
    }
    const image = decodePng(readFileSync(png));
    if (image.width !== g.cols || image.height !== g.rows) throw new Error(`gerbv drew ${image.width} × ${image.height}, not ${g.cols} × ${g.rows}`);
    const cells = new Uint8Array(g.cols * g.rows);
    for (let i = 0; i < cells.length; i++) cells[i] = image.pixels[i * image.channels] > 127 ? 1 : 0;
    return cells;
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/**
 * The holes gerbv reads from a drill file, from its Excellon export: inches with four decimals, zeros kept
 * ("INCH,TZ", X015945Y002469), each tool's diameter in its header. Millimetres here, as ours.
 */
export function gerbvHoles(path: string): Hole[] {
  return gerbvDrill(path).holes;
}

/** gerbv's holes and slots (G85) of a drill file, from its Excellon export. */
export function gerbvDrill(path: string): { holes: Hole[]; slots: Slot[] } {
  const dir = mkdtempSync(join(tmpdir(), 'gerbv-'));
  try {
    const out = join(dir, 'holes.drl');
    try {
      execFileSync('gerbv', ['-x', 'drill', '-o', out, path], { stdio: 'pipe', timeout: 120_000 });
    } catch (e) {
      if (!existsPng(out)) throw e;
    }
    return readGerbvExcellon(readFileSync(out, 'latin1'));
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

/** gerbv's Excellon export read back: its holes and its G85 slots. */
export function readGerbvExcellon(text: string): { holes: Hole[]; slots: Slot[] } {
  if (!/^INCH,TZ\s*$/m.test(text)) throw new Error('gerbv wrote its drill file in a format this reader does not know');
  const tools = new Map<string, number>();
  const holes: Hole[] = [];
  const slots: Slot[] = [];
  let tool = '';
  const inch = (v: string) => (v.includes('.') ? Number(v) : Number(v) / 1e4) * 25.4;
  for (const line of text.split(/\r?\n/)) {
    let m: RegExpExecArray | null;
    if ((m = /^T(\d+)C([\d.]+)/.exec(line))) tools.set(m[1], Number(m[2]) * 25.4);
    else if ((m = /^T(\d+)$/.exec(line))) tool = m[1];
    else if ((m = /^X([-+]?[\d.]+)Y([-+]?[\d.]+)$/.exec(line))) holes.push({ x: inch(m[1]), y: inch(m[2]), diameterMm: tools.get(tool) ?? 0 });
    // "X001001Y003903G85X001237Y003903": a slot, the tool's diameter from its header.
    else if ((m = /^X([-+]?[\d.]+)Y([-+]?[\d.]+)G85X([-+]?[\d.]+)Y([-+]?[\d.]+)$/.exec(line)))
      slots.push({ x0: inch(m[1]), y0: inch(m[2]), x1: inch(m[3]), y1: inch(m[4]), diameterMm: tools.get(tool) ?? 0 });
  }
  return { holes, slots };
}

/** The holes in gerbv's Excellon export (for its unit test). */
export function readGerbvDrill(text: string): Hole[] {
  return readGerbvExcellon(text).holes;
}

export interface HoleMatch {
  /** gerbv's holes with one of ours within the tolerance (each of ours matched once). */
  matched: number;
  /** The furthest any of gerbv's holes lies from the nearest of ours, mm. */
  worstMm: number;
  /** Our diameters, mm to 4 decimals, of matched holes whose size differs from gerbv's by more than the diameter tolerance. */
  diametersDiffering: number[];
}

/** Pairs each of gerbv's holes with the nearest unpaired one of ours. */
export function matchHoles(ours: readonly Hole[], theirs: readonly Hole[], toleranceMm: number, diameterToleranceMm: number): HoleMatch {
  const used = new Uint8Array(ours.length);
  let matched = 0, worstMm = 0;
  const differing = new Set<number>();
  for (const h of theirs) {
    let best = -1, bestD = Infinity;
    for (let i = 0; i < ours.length; i++) {
      if (used[i]) continue;
      const d = Math.hypot(ours[i].x - h.x, ours[i].y - h.y);
      if (d < bestD) (bestD = d), (best = i);
    }
    worstMm = Math.max(worstMm, bestD);
    if (best >= 0 && bestD <= toleranceMm) {
      used[best] = 1;
      matched++;
      if (Math.abs(ours[best].diameterMm - h.diameterMm) > diameterToleranceMm) differing.add(+ours[best].diameterMm.toFixed(4));
    }
  }
  return { matched, worstMm, diametersDiffering: [...differing].sort((a, b) => a - b) };
}

function existsPng(path: string): boolean {
  try {
    return readFileSync(path).length > 0;
  } catch {
    return false;
  }
}

/** An 8-bit PNG, truecolour or grey, with or without alpha, not interlaced: what gerbv writes. */
export function decodePng(bytes: Buffer): { width: number; height: number; channels: number; pixels: Uint8Array } {
  let width = 0;
  let height = 0;
  let channels = 0;
  const idat: Buffer[] = [];
  for (let i = 8; i < bytes.length; ) {
    const len = bytes.readUInt32BE(i);
    const type = bytes.toString('latin1', i + 4, i + 8);
    const data = bytes.subarray(i + 8, i + 8 + len);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      if (data[8] !== 8 || data[12] !== 0) throw new Error('only 8-bit, non-interlaced PNGs');
      channels = ({ 0: 1, 2: 3, 4: 2, 6: 4 } as Record<number, number>)[data[9]] ?? 0;
      if (!channels) throw new Error(`PNG colour type ${data[9]} is not handled`);
    } else if (type === 'IDAT') {
      idat.push(data);
    }
    i += 12 + len;
  }
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const pixels = new Uint8Array(stride * height);
  for (let y = 0; y < height; y++) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    const out = pixels.subarray(y * stride, (y + 1) * stride);
    const up = y > 0 ? pixels.subarray((y - 1) * stride, y * stride) : new Uint8Array(stride);
    for (let x = 0; x < stride; x++) {
      const a = x >= channels ? out[x - channels] : 0;
      const b = up[x];
      const c = x >= channels ? up[x - channels] : 0;
      const p = a + b - c;
      const predictor = [0, a, b, (a + b) >> 1, Math.abs(p - a) <= Math.abs(p - b) && Math.abs(p - a) <= Math.abs(p - c) ? a : Math.abs(p - b) <= Math.abs(p - c) ? b : c][filter];
      out[x] = (line[x] + predictor) & 255;
    }
  }
  return { width, height, channels, pixels };
}

export interface Agreement {
  /** Cells at least one cell away from any edge of gerbv's picture (their 3 × 3 neighbourhood is all one value). */
  interior: number;
  interiorAgree: number;
  all: number;
  allAgree: number;
}

export function agreement(ours: Uint8Array, theirs: Uint8Array, cols: number, rows: number): Agreement {
  const a: Agreement = { interior: 0, interiorAgree: 0, all: cols * rows, allAgree: 0 };
  for (let r = 0; r < rows; r++) {
    for (let c = 0; c < cols; c++) {
      const i = r * cols + c;
      const same = ours[i] === theirs[i];
      if (same) a.allAgree++;
      if (!onEdge(theirs, cols, rows, r, c)) {
        a.interior++;
        if (same) a.interiorAgree++;
      }
    }
  }
  return a;
}

/** Whether the cell at row r, column c lies on an edge of a picture: its 3 × 3 neighbourhood is not all one value. */
export function onEdge(picture: Uint8Array, cols: number, rows: number, r: number, c: number): boolean {
  const v = picture[r * cols + c];
  for (let rr = Math.max(0, r - 1); rr <= Math.min(rows - 1, r + 1); rr++) {
    for (let cc = Math.max(0, c - 1); cc <= Math.min(cols - 1, c + 1); cc++) if (picture[rr * cols + cc] !== v) return true;
  }
  return false;
}
