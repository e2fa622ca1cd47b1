// A small exposure job for trying the machine: a frame, a cross and a grey ramp, 48 × 32 cells.

import type { PrintJob } from '../protocol/job-types';

/** Where the pattern lands on the bed, its corner in µm; 4.8 × 3.2 mm at the 100 µm pitch. */
export const TEST_PATTERN_ORIGIN_UM = { x: 20000, y: 20000 };

/** `fullUs`: a cell's exposure at 100 % dose, the Job panel's full dose. */
export function testPattern(fullUs: number): PrintJob {
  const cols = 48, rows = 32;
  const gridData = Array.from({ length: rows }, (_, y) =>
    Array.from({ length: cols }, (_, x) => {
      if (x === 0 || y === 0 || x === cols - 1 || y === rows - 1) return 255;
      if (Math.abs(x - y * 1.5) < 1 || Math.abs(x - (cols - 1 - y * 1.5)) < 1) return 255;
      if (y > 24 && y < 29 && x > 4 && x < 43) return Math.round(((x - 5) / 37) * 255);
      return 0;
    }),
  );
  return {
    name: 'test-pattern',
    grid: { cols, rows },
    pitchUm: { x: 100, y: 100 },
    originUm: { ...TEST_PATTERN_ORIGIN_UM },
    dose: { map: 'linear', fullUs },
    leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'serpentine' },
    gridData,
  };
}
