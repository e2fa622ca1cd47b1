// Property tests of the TypeScript in app/src/protocol/ against generated and hostile input
// (fast-check): the counterpart of the C++ fuzzers in firmware/fuzz/, which take what only the firmware
// reads (the dialect's frames and commands in mega_link and mega_machine, the printhead link in
// nano_line and printhead_link). Nothing throws on any input, and what is made is read back as it was
// or has the shape its reader takes.
import fc from 'fast-check';
import { crc32 } from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { crc16Hex } from './crc16';
import { encodeFrame } from './dialect-frame';
import { formatMilli, parseMilli } from './dialect-number';
import { parseReply } from './dialect-reply';
import { encodeJob } from './job-encode';
import { JOB_LIMITS, type PrintJob, type StrategyName } from './job-types';
import { LineSplitter, type SplitLine } from './line-splitter';

const runs = { numRuns: 400 };
const anyText = fc.string({ unit: 'binary', maxLength: 200 });
const bodyChar = fc.constantFrom(...'GM0123456789 XYZSPF.-abcN'.split(''));
const body = fc.string({ unit: bodyChar, minLength: 1, maxLength: 60 }).filter((s) => s.trim() === s && !s.includes('  '));
/** Bytes with line ends among them, often enough that lines of every length end. */
const wire = fc.array(fc.oneof(anyText, fc.constantFrom('\n', '\r\n', '\r')), { maxLength: 12 }).map((parts) => parts.join(''));

/** The lines a stream holds: one `\r` before a `\n` dropped (mega.md §1), a line past the limit cut to it and flagged, a tail without its `\n` left waiting. */
function linesOf(bytes: string, maxLine: number): SplitLine[] {
  return bytes.split('\n').slice(0, -1).map((l) => {
    const text = l.endsWith('\r') ? l.slice(0, -1) : l;
    return { text: text.slice(0, maxLine), overflow: text.length > maxLine };
  });
}

describe('the dialect against hostile bytes', () => {
  it('splits any bytes into the same lines wherever the chunks break, each within its limit', () => {
    fc.assert(fc.property(wire, fc.nat(), fc.integer({ min: 1, max: 40 }), (bytes, at, maxLine) => {
      const cut = at % (bytes.length + 1);
      const s = new LineSplitter(maxLine);
      expect([...s.push(bytes.slice(0, cut)), ...s.push(bytes.slice(cut))]).toEqual(linesOf(bytes, maxLine));
    }), runs);
  });

  it('parses any reply line without throwing', () => {
    fc.assert(fc.property(anyText, (line) => void parseReply(line)), runs);
  });

  it('reads back every number it writes', () => {
    fc.assert(fc.property(fc.integer({ min: -2_000_000_000, max: 2_000_000_000 }), (v) => {
      expect(parseMilli(formatMilli(v))).toBe(v);
    }), runs);
  });

  it('writes every numbered frame in the shape of mega.md §1, its checks over all before the `*`', () => {
    // 2147483646: the last line number (mega.md §1).
    fc.assert(fc.property(fc.integer({ min: 0, max: 2147483646 }), body, (n, b) => {
      const m = /^(N([0-9]+) (.*))\*([0-9]{1,3})#([0-9a-f]{4})$/.exec(encodeFrame(n, b));
      expect(m?.slice(2, 4)).toEqual([String(n), b]);
      const head = m![1];
      expect(Number(m![4])).toBe([...head].reduce((x, ch) => x ^ ch.charCodeAt(0), 0));
      expect(m![5]).toBe(crc16Hex(head));
    }), runs);
  });
});

const strategies: StrategyName[] = ['raster', 'serpentine', 'shortest', 'random', 'scan'];
const job: fc.Arbitrary<PrintJob> = fc.record({ cols: fc.integer({ min: 1, max: 40 }), rows: fc.integer({ min: 1, max: 12 }) }).chain(({ cols, rows }) =>
  fc.record({
    grid: fc.constant({ cols, rows }),
    pitchUm: fc.record({ x: fc.integer({ min: 1, max: 1000 }), y: fc.integer({ min: 1, max: 1000 }) }),
    originUm: fc.record({ x: fc.integer({ min: 0, max: 200000 }), y: fc.integer({ min: 0, max: 200000 }) }),
    dose: fc.record({ map: fc.constant('linear' as const), fullUs: fc.integer({ min: 1, max: 10_000_000 }) }),
    leds: fc.constant({ offsets: [[0, 0], [1, 0], [0, 1], [1, 1]] as [number, number][] }),
    strategy: fc.record({ name: fc.constantFrom(...strategies) }),
    gridData: fc.array(fc.array(fc.oneof(fc.constant(0), fc.integer({ min: 0, max: 255 })), { minLength: cols, maxLength: cols }), { minLength: rows, maxLength: rows }),
  }),
);

// The job text is read only by the firmware (the Mega, the ESP): the drawn jobs of job.json carry the
// round trip, the encoder writing them here byte for byte and the C++ verifier reading them back to
// their cells and refusing them cut short (job_test.cpp), and the job_text fuzzer runs the verifier on
// any bytes. Here: the encoder writes any job as records a line each, closed by the CRC-32 of the rest.
describe('the job text of any job', () => {
  it('is records within a line each, ending in the CRC-32 of everything before the end line (zlib\'s)', () => {
    fc.assert(fc.property(job, (j) => {
      const text = encodeJob(j);
      const lines = text.split('\n');
      expect(lines.pop()).toBe('');
      for (const line of lines) expect(line.length).toBeLessThanOrEqual(JOB_LIMITS.maxRecordBytes);
      const end = lines.pop()!;
      expect(end).toBe(`end ${crc32(lines.map((l) => l + '\n').join('')).toString(16).padStart(8, '0')}`);
      expect(lines.slice(0, 2)).toEqual(['uvj 1', `grid ${j.grid.cols} ${j.grid.rows}`]);
    }), { numRuns: 150 });
  });
});
