// The upload's size and time as the question says them: bytes as the printer's format writes them, framed lines, rate.
import { describe, expect, it } from 'vitest';
import { encodeFrame } from '../protocol/dialect-frame';
import { encodeJob } from '../protocol/job-encode';
import type { PrintJob } from '../protocol/job-types';
import { bytesText, LINE_RATE, rateText, uploadBytes, uploadLeftS, uploadUs } from './link-rate';
import { uploadSize } from './upload-time';

const filled = (cols: number, rows: number): PrintJob => ({
  grid: { cols, rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 0, y: 0 }, dose: { map: 'threshold', level: 128, fullUs: 4000 },
  leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] }, strategy: { name: 'serpentine' }, gridData: Array.from({ length: rows }, () => new Uint8Array(cols).fill(255)),
});

describe('upload size and time', () => {
  it('counts the job text and each record as a numbered line with its checks', () => {
    const job = filled(40, 3);
    for (const format of [1, 2] as const) {
      const text = encodeJob(job, format);
      const lines = text.trimEnd().split('\n');
      const size = uploadSize(job, format);
      expect(size.textBytes).toBe(text.length);
      expect(size.records).toBe(lines.length);
      expect(size.wireBytes).toBe(lines.reduce((n, l, i) => n + encodeFrame(i + 1, l).length + 1, 0));
      expect(size.cells).toBe(120);
    }
  });

  it('a filled 600 x 600 job: about 1 MB on the wire as hex rows, under 20 KB as run-length rows', () => {
    const job = filled(600, 600);
    expect(uploadSize(job, 1).wireBytes).toBeGreaterThan(990_000);
    expect(uploadSize(job, 2).wireBytes).toBeLessThan(20_000);
    expect(uploadUs(uploadSize(job, 1).wireBytes, LINE_RATE) / 1e6).toBeGreaterThan(85); // the 85 s
  });

  it('says the rate, the bytes and the time left in words', () => {
    expect(rateText(LINE_RATE)).toBe("11.5 KB/s, the line's rate (no upload measured yet)");
    expect(rateText({ bytesPerS: 9800, measured: true })).toBe('9.8 KB/s, as measured on the last upload');
    expect(bytesText(998_367)).toBe('998 KB');
    expect(bytesText(1_014_060)).toBe('1.01 MB');
    expect(bytesText(9663)).toBe('9.7 KB');
    expect(uploadLeftS({ bytesSent: 0, bytesTotal: 10 })).toBeNull();
    expect(uploadLeftS({ bytesSent: 500, bytesTotal: 1000, wireSent: 1000, wireTotal: 21_000, bytesPerS: 10_000 })).toBe(2);
  });
});

describe('the rate the ESP measures', () => {
  it('counts job text, as the hub reports it, so the time is the text over that rate', () => {
    const size = uploadSize(filled(600, 10), 1);
    const rate = { bytesPerS: 10_000, measured: true, counts: 'text' as const };
    expect(uploadBytes(size, rate)).toBe(size.textBytes);
    expect(uploadBytes(size, LINE_RATE)).toBe(size.wireBytes);
    expect(uploadUs(uploadBytes(size, rate), rate)).toBe(Math.round((size.textBytes / 10_000) * 1e6));
  });
});
