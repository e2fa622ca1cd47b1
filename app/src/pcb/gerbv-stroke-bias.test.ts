// Why the corpus test lets gerbv's picture move a quarter cell (corpus-boards.ts, GERBV_STROKE_BIAS): gerbv
// draws thin strokes, without antialiasing, a little right of and below where they are. Ours are exact
// (a cell is lit when the stroke covers half of it), so on a board of thin traces the two disagree along
// one side of each trace. Node only, with gerbv.
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { GERBV_STROKE_BIAS } from './corpus-boards';
import { agreement, gerbvCells, hasGerbv } from './gerbv-reference';
import { rasteriseBoard } from './rasterise';
import { readBoard } from './read-board';

/** 200 strokes 0.15 mm wide, across and along, at places that fall anywhere within a 50 µm cell. */
function thinStrokes(): string {
  let seed = 1;
  const next = (lo: number, hi: number) => lo + ((seed = (seed * 48271) % 2147483647) % (hi - lo + 1));
  const lines = ['%MOIN*%', '%FSLAX34Y34*%', '%ADD10C,0.0059*%', 'G01*', 'D10*'];
  for (let i = 0; i < 200; i++) {
    const [x, y, run] = [next(8000, 13000), -next(8000, 13000), next(200, 900)];
    lines.push(`X${x}Y${y}D02*`, i % 2 ? `X${x + run}Y${y}D01*` : `X${x}Y${y - run}D01*`);
  }
  return [...lines, 'M02*', ''].join('\n');
}

describe.runIf(hasGerbv())("gerbv's thin strokes", () => {
  const text = thinStrokes();
  const path = join(mkdtempSync(join(tmpdir(), 'gerbv-bias-')), 'strokes.gbr');
  writeFileSync(path, text);
  const set = readBoard([{ name: 'strokes.gtl', text }]);
  const [p, cols, rows, x0, y0] = [0.05, 400, 400, 19, -35];
  const ours = rasteriseBoard(set, { expose: ['strokes.gtl'], pitchUm: { x: 50, y: 50 }, threshold: 0.5, windowMm: { x0, y0, x1: x0 + cols * p, y1: y0 + rows * p } }).cells;

  it('lie right of and below ours: a cell only gerbv lights has ours lit on its left or above, seldom the other way', () => {
    const theirs = gerbvCells(path, { cols, rows, x0, y0, pitchMm: p });
    let [leftOrAbove, rightOrBelow] = [0, 0];
    for (let r = 1; r < rows - 1; r++) {
      for (let c = 1; c < cols - 1; c++) {
        const i = r * cols + c;
        if (ours[i] || !theirs[i]) continue;
        if (ours[i - 1] || ours[i - cols]) leftOrAbove++;
        if (ours[i + 1] || ours[i + cols]) rightOrBelow++;
      }
    }
    expect(leftOrAbove).toBeGreaterThan(5 * rightOrBelow);
  });

  it('agree better with ours once gerbv draws a quarter cell the other way', () => {
    const at = (d: number) => agreement(ours, gerbvCells(path, { cols, rows, x0: +(x0 + d * p).toFixed(4), y0: +(y0 - d * p).toFixed(4), pitchMm: p }), cols, rows).allAgree;
    expect(at(GERBV_STROKE_BIAS)).toBeGreaterThan(at(0));
  });
});
