// Streaming verifier of job text (protocol/job.md): record syntax, order, bounds and the whole-job CRC.

import { crc32Hex, crc32Update } from './crc32';
import { parseRunTokens } from './job-runs';
import { JOB_LIMITS, STRATEGY_NAMES, type JobFormat, type JobHeader, type StrategyName } from './job-types';

export type JobError = { code: 23 | 24 | 25; line: number; message: string };

export interface Segment {
  row: number;
  col: number;
  cells: Uint8Array;
}

const NUM = /^(0|-?[1-9][0-9]*)$/;
const STRATEGIES = new Set<string>(STRATEGY_NAMES);

/** Integer field in [lo, hi], or null. */
function int(s: string | undefined, lo: number, hi: number): number | null {
  if (s === undefined || !NUM.test(s) || s.length > 11) return null;
  const v = Number(s);
  return v >= lo && v <= hi ? v : null;
}

function ints(words: string[], count: number, lo: number, hi: number): number[] | null {
  if (words.length !== count) return null;
  const out = words.map((w) => int(w, lo, hi));
  return out.every((v) => v !== null) ? (out as number[]) : null;
}

/**
 * Feed records one at a time (without '\n'). The first error sticks; after it every call
 * returns it. `finish()` reports a job that stopped before `end`.
 */
export class JobVerifier {
  #index = 0;
  #crc = 0;
  #lineNo = 0;
  #ended = false;
  #error: JobError | null = null;
  #prevRow = -1;
  #prevEnd = 0;
  #format: JobFormat = 1;
  #header: JobHeader = {
    cols: 0, rows: 0, pitchUm: [0, 0], originUm: [0, 0], map: 'linear', level: 0,
    gainPermille: [], thermal: [0, 250], offsets: [], strategy: 'raster', seed: 0,
  };

  constructor(private readonly onSegment?: (s: Segment) => void) {}

  get header(): JobHeader | null {
    return this.#index >= 10 && !this.#error ? this.#header : null;
  }

  get error(): JobError | null {
    return this.#error;
  }

  get complete(): boolean {
    return this.#ended && !this.#error;
  }

  push(record: string): JobError | null {
    if (this.#error) return this.#error;
    this.#lineNo++;
    if (this.#ended) return this.#fail(25, 'bytes after end');
    const words = record.split(' ');
    if (words[0] === 'end') return this.#end(words);
    const problem = this.#index < 10 ? this.#headerRecord(words) : this.#segment(words);
    if (problem) return this.#fail(23, problem);
    this.#crc = crc32Update(this.#crc, record + '\n');
    return null;
  }

  finish(): JobError | null {
    if (this.#error) return this.#error;
    if (!this.#ended) return this.#fail(25, 'job stops before end');
    return null;
  }

  #fail(code: 23 | 24 | 25, message: string): JobError {
    this.#error = { code, line: this.#lineNo, message };
    return this.#error;
  }

  #end(words: string[]): JobError | null {
    if (this.#index < 10) return this.#fail(23, 'end before the header is complete');
    if (words.length !== 2 || !/^[0-9a-f]{8}$/.test(words[1])) return this.#fail(23, 'end needs 8 lower-case hex digits');
    this.#ended = true;
    if (words[1] !== crc32Hex(this.#crc)) return this.#fail(24, `hash ${crc32Hex(this.#crc)} != ${words[1]}`);
    return null;
  }

  /** Record #index of the fixed header order; returns a problem or null. */
  #headerRecord(w: string[]): string | null {
    const h = this.#header;
    const expect = ['uvj', 'grid', 'pitch', 'origin', 'map', 'dose', 'gain', 'thermal', 'leds', 'strategy'][this.#index];
    const key = w[0] === 'full' || w[0] === 'target' ? 'dose' : w[0];
    if (key !== expect) return `expected ${expect}, got ${w[0]}`;
    const rest = w.slice(1);
    let ok = true;
    switch (key) {
      case 'uvj':
        ok = rest.length === 1 && (rest[0] === '1' || rest[0] === '2');
        if (ok) this.#format = Number(rest[0]) as JobFormat;
        break;
      case 'grid': {
        const v = ints(rest, 2, 1, JOB_LIMITS.maxSide);
        if ((ok = !!v)) [h.cols, h.rows] = v!;
        break;
      }
      case 'pitch': {
        const v = ints(rest, 2, 1, 100000);
        if ((ok = !!v)) h.pitchUm = [v![0], v![1]];
        break;
      }
      case 'origin': {
        const v = ints(rest, 2, 0, 10000000);
        if ((ok = !!v)) h.originUm = [v![0], v![1]];
        break;
      }
      case 'map':
        if (rest.length === 1 && rest[0] === 'linear') h.map = 'linear';
        else if (rest.length === 2 && rest[0] === 'threshold' && int(rest[1], 1, 255) !== null) {
          h.map = 'threshold';
          h.level = Number(rest[1]);
        } else ok = false;
        break;
      case 'dose':
        if (w[0] === 'full') {
          const v = ints(rest, 1, 1, 10000000);
          if ((ok = !!v)) h.fullUs = v![0];
        } else {
          const t = rest.length === 5 ? int(rest[0], 1, 100000000) : null;
          const irr = ints(rest.slice(1), 4, 1, 10000000);
          if ((ok = t !== null && !!irr)) {
            h.targetUJcm2 = t!;
            h.irradianceUWcm2 = irr!;
          }
        }
        break;
      case 'gain': {
        const v = ints(rest, 4, 1, 10000);
        if ((ok = !!v)) h.gainPermille = v!;
        break;
      }
      case 'thermal': {
        const c = rest.length === 2 ? int(rest[0], -1000, 1000) : null;
        const ref = int(rest[1], -400, 1250);
        if ((ok = c !== null && ref !== null)) h.thermal = [c!, ref!];
        break;
      }
      case 'leds': {
        const v = ints(rest, 8, -4096, 4096);
        if ((ok = !!v)) h.offsets = [0, 1, 2, 3].map((i) => [v![i * 2], v![i * 2 + 1]] as [number, number]);
        break;
      }
      case 'strategy': {
        const seed = rest.length === 2 ? int(rest[1], 0, 4294967295) : null;
        ok = STRATEGIES.has(rest[0]) && seed !== null && (rest[0] === 'random' || seed === 0);
        if (ok) {
          h.strategy = rest[0] as StrategyName;
          h.seed = seed!;
        }
        break;
      }
    }
    if (!ok) return `bad ${key} record`;
    this.#index++;
    return null;
  }

  /** The format's version, 1 or 2, once `uvj` has been read. */
  get format(): JobFormat {
    return this.#format;
  }

  #segment(w: string[]): string | null {
    if (w[0] === 'rl' && this.#format >= 2) return this.#runs(w);
    if (w[0] !== 'r') return `unknown record ${w[0]}`;
    const h = this.#header;
    const row = int(w[1], 0, h.rows - 1);
    const col = int(w[2], 0, h.cols - 1);
    const hex = w[3];
    if (w.length !== 4 || row === null || col === null) return 'bad r record';
    if (!/^(?:[0-9a-f]{2})+$/.test(hex) || hex.length > JOB_LIMITS.maxCellsPerRecord * 2) return 'bad cell hex';
    const n = hex.length / 2;
    return this.#place(row, col, n, (cells) => {
      for (let i = 0; i < n; i++) cells[i] = parseInt(hex.substr(i * 2, 2), 16);
    });
  }

  /** A segment of `n` cells at (`row`, `col`): on the grid, after the last one; `fill` writes its cells. */
  #place(row: number, col: number, n: number, fill: (cells: Uint8Array) => void): string | null {
    if (col + n > this.#header.cols) return 'segment past the grid';
    if (row < this.#prevRow || (row === this.#prevRow && col < this.#prevEnd)) return 'segment out of order or overlapping';
    this.#prevRow = row;
    this.#prevEnd = col + n;
    if (this.onSegment) {
      const cells = new Uint8Array(n);
      fill(cells);
      this.onSegment({ row, col, cells });
    }
    return null;
  }

  /** `rl <row> <col> <token>…` (job.md "Run-length rows"). */
  #runs(w: string[]): string | null {
    const h = this.#header;
    const row = int(w[1], 0, h.rows - 1);
    const col = int(w[2], 0, h.cols - 1);
    if (w.length < 4 || row === null || col === null) return 'bad rl record';
    if (w.join(' ').length > JOB_LIMITS.maxRecordBytes) return 'rl record over 76 bytes';
    const n = parseRunTokens(w.slice(3));
    if (n === null) return 'bad rl token';
    return this.#place(row, col, n, (cells) => parseRunTokens(w.slice(3), (at, value, count) => cells.fill(value, at, at + count)));
  }
}

/** Verifies a whole job text; the last line must end in '\n'. */
export function verifyJobText(text: string, onSegment?: (s: Segment) => void): { error: JobError | null; header: JobHeader | null } {
  const v = new JobVerifier(onSegment);
  const lines = text.split('\n');
  const tail = lines.pop();
  for (const line of lines) if (v.push(line)) break;
  let error = v.error;
  if (!error && tail !== '') error = { code: 25, line: lines.length + 1, message: 'last line has no newline' };
  error ??= v.finish();
  return { error, header: error ? null : v.header };
}
