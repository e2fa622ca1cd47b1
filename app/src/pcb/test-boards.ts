// Test support: small Gerber files written by hand in millimetres, and ways to look at the cells they give.
import type { BoardRaster } from './rasterise';
import { readBoard, type BoardSet } from './read-board';

/** A coordinate in %FSLAX46Y46 units (millionths of a millimetre). */
export const mm = (v: number): string => String(Math.round(v * 1e6));
export const at = (x: number, y: number): string => `X${mm(x)}Y${mm(y)}`;

/** A metric Gerber file around the given body (apertures and draws, one command a line). */
export function gerber(body: string): string {
  return `G04 written by hand for a test*\n%FSLAX46Y46*%\n%MOMM*%\n${body.trim()}\nM02*\n`;
}

/** One file read as a board; fails the test if the file had a problem. */
export function boardOf(text: string, name = 'test.gbr'): BoardSet {
  const set = readBoard([{ name, text }]);
  if (set.problems.length) throw new Error(set.problems.map((p) => p.message).join('; '));
  return set;
}

/** The cells as rows of '#' (exposed) and '.', top row first. */
export function picture(r: BoardRaster): string[] {
  return Array.from({ length: r.rows }, (_, y) => Array.from(r.cells.subarray(y * r.cols, (y + 1) * r.cols), (v) => (v ? '#' : '.')).join(''));
}

/** The covered area the coverage adds up to, mm². */
export function coveredArea(r: BoardRaster): number {
  const cell = ((r.windowMm.x1 - r.windowMm.x0) / r.cols) * ((r.windowMm.y1 - r.windowMm.y0) / r.rows);
  return r.coverage.reduce((a, c) => a + c, 0) * cell;
}

export const count = (r: BoardRaster): number => r.cells.reduce((a, c) => a + c, 0);
