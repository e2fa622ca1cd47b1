// Property tests of the TypeScript codecs against generated and hostile input (fast-check): the
// counterpart of the C++ fuzzers in firmware/fuzz/. Nothing throws on any input, and what is
// made is read back as it was.
import fc from 'fast-check';
import { crc32 } from 'node:zlib';
import { describe, expect, it } from 'vitest';
import { MAX_MILLI, parseCommand } from './dialect-command';
import { encodeFrame, MAX_LINE_NUMBER, parseFrame } from './dialect-frame';
import { parseReply } from './dialect-reply';
import { encodeJob } from './job-encode';
import { JOB_LIMITS, type PrintJob, type StrategyName } from './job-types';
import { LineSplitter } from './line-splitter';
import { formatNanoCommand, formatNanoReply, parseNanoCommand, parseNanoReply, type NanoCommand } from './nano';
import { validatePrintRequest } from './print-request';

const runs = { numRuns: 400 };
const anyText = fc.string({ unit: 'binary', maxLength: 200 });
const bodyChar = fc.constantFrom(...'GM0123456789 XYZSPF.-abcN'.split(''));
const body = fc.string({ unit: bodyChar, minLength: 1, maxLength: 60 }).filter((s) => s.trim() === s && !s.includes('  '));

describe('the dialect against hostile bytes', () => {
  it('splits, frames and parses any bytes without throwing, every number in its range', () => {
    fc.assert(fc.property(fc.array(anyText, { maxLength: 8 }), (chunks) => {
      const splitter = new LineSplitter(96);
      for (const chunk of chunks) {
        for (const line of splitter.push(chunk)) {
          const f = parseFrame(line);
          if (f.n !== undefined) expect(f.n >= -1 && f.n <= MAX_LINE_NUMBER).toBe(true);
          if (!f.ok) continue;
          const c = parseCommand(f.body);
          if (c.ok && 'params' in c.command)
            for (const v of Object.values(c.command.params)) if (v !== null) expect(Math.abs(v)).toBeLessThanOrEqual(MAX_MILLI);
        }
      }
    }), runs);
  });

  it('reads back every numbered frame it writes', () => {
    fc.assert(fc.property(fc.integer({ min: 0, max: MAX_LINE_NUMBER }), body, (n, b) => {
      const f = parseFrame({ text: encodeFrame(n, b), overflow: false });
      if (encodeFrame(n, b).length > 96) return;
      expect(f).toEqual({ ok: true, n, body: b });
    }), runs);
  });

  it('parses any reply line without throwing', () => {
    fc.assert(fc.property(anyText, (line) => void parseReply(line)), runs);
  });
});

const fire: fc.Arbitrary<NanoCommand> = fc.record({
  op: fc.constant('F' as const),
  mask: fc.integer({ min: 0, max: 15 }),
  durations: fc.tuple(...[0, 1, 2, 3].map(() => fc.integer({ min: 0, max: 0xffffffff }))) as fc.Arbitrary<[number, number, number, number]>,
});

describe('the printhead link against hostile bytes', () => {
  it('reads back every command it writes, and parses any line without throwing', () => {
    fc.assert(fc.property(fc.oneof(fire, fc.constantFrom(...'SDUXPTREVC'.split('')).map((op) => ({ op }) as NanoCommand)), (cmd) => {
      const text = formatNanoCommand(cmd);
      expect(parseNanoCommand(text.slice(0, -1))).toEqual(cmd);
    }), runs);
    fc.assert(fc.property(anyText, (line) => {
      void parseNanoCommand(line);
      const r = parseNanoReply(line + '\n');
      if (r) expect(parseNanoReply(formatNanoReply(r))).toEqual(r);
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

describe('POST /print against hostile bodies', () => {
  it('answers any body with a verdict and never throws; a refusal names its place', () => {
    const jsonish = fc.oneof(anyText, fc.json(), fc.jsonValue().map((v) => JSON.stringify({ gridData: v, grid: v, dose: v })));
    fc.assert(fc.property(jsonish, (b) => {
      const r = validatePrintRequest(b);
      expect([202, 400, 413]).toContain(r.status);
      if (r.status !== 202) expect(typeof r.error).toBe('string');
    }), runs);
  });
});
