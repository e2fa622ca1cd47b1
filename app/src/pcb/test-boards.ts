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

/** A made-up but busy top copper layer: pads, traces with bends and arcs, and two pours with clearances. */
export function busyBoard(): string {
  let seed = 1;
  const random = () => ((seed = (seed * 16807) % 2147483647) - 1) / 2147483646;
  const lines = ['%ADD10C,0.2*%', '%ADD11C,1.6X0.8*%', '%ADD12R,1.5X0.6*%', '%ADD13O,0.6X1.8*%', '%ADD14C,0.3*%', 'G75*'];
  // Two pours, each a region with an arc, and clearances cut into them with LPC.
  for (const [x0, y0] of [
    [2, 2],
    [52, 2],
  ]) {
    lines.push('G36*', `${at(x0, y0)}D02*`, 'G01*', `${at(x0 + 46, y0)}D01*`, `${at(x0 + 46, y0 + 30)}D01*`, 'G03*', `${at(x0 + 36, y0 + 40)}I-10000000J0D01*`, 'G01*', `${at(x0, y0 + 40)}D01*`, `${at(x0, y0)}D01*`, 'G37*');
  }
  lines.push('%LPC*%', 'D14*');
  for (let i = 0; i < 800; i++) lines.push(`${at(3 + random() * 94, 3 + random() * 38)}D03*`);
  lines.push('%LPD*%', 'D11*');
  for (let i = 0; i < 600; i++) lines.push(`${at(2 + random() * 96, 2 + random() * 76)}D03*`);
  lines.push('D12*');
  for (let i = 0; i < 400; i++) lines.push(`${at(2 + random() * 96, 44 + random() * 34)}D03*`);
  lines.push('D13*');
  for (let i = 0; i < 200; i++) lines.push(`${at(2 + random() * 96, 44 + random() * 34)}D03*`);
  // 1500 traces of four bends each, some ending in an arc.
  lines.push('D10*');
  for (let i = 0; i < 1500; i++) {
    let x = 2 + random() * 96;
    let y = 44 + random() * 34;
    lines.push(`${at(x, y)}D02*`, 'G01*');
    for (let k = 0; k < 4; k++) {
      x = Math.min(98, Math.max(2, x + (random() - 0.5) * 10));
      y = Math.min(78, Math.max(44, y + (random() - 0.5) * 10));
      lines.push(`${at(x, y)}D01*`);
    }
    if (i % 5 === 0) lines.push('G02*', `${at(x + 2, y)}I1000000J0D01*`);
  }
  return gerber(lines.join('\n'));
}
