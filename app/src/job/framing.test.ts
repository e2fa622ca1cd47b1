import { describe, expect, it } from 'vitest';
import type { PrintJob } from '../protocol/job-types';
import { framingMoves } from './framing';

const job = (offsets: [number, number][]): PrintJob => ({
  grid: { cols: 200, rows: 50 },
  pitchUm: { x: 50, y: 100 },
  originUm: { x: 10_000, y: 2_500 },
  dose: { map: 'linear', fullUs: 1000 },
  leds: { offsets },
  strategy: { name: 'raster' },
  gridData: [],
});

describe('framingMoves', () => {
  it('goes round the cells clockwise from the origin and back, absolute, at the travel speed', () => {
    expect(framingMoves(job([[0, 0]]), 100)).toEqual([
      'G90',
      'G0 X10 Y2.5 F6000',
      'G0 X20 Y2.5 F6000',
      'G0 X20 Y7.5 F6000',
      'G0 X10 Y7.5 F6000',
      'G0 X10 Y2.5 F6000',
    ]);
  });

  it('puts the first LED on the corners, wherever it sits on the head', () => {
    // LED 0 two cells right and one down of the head origin: the head stands back by as much.
    expect(framingMoves(job([[2, 1]]), 50)[1]).toBe('G0 X9.9 Y2.4 F3000');
  });
});
