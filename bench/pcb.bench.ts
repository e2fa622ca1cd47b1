// B3: a Gerber board to cells, 100 × 80 mm of busy copper (41 600 shapes) at 50 µm (2000 × 1600 cells),
// against a plain pass writing every cell of the same grid.
import { rasteriseBoard } from '../app/src/pcb/rasterise';
import { readBoard } from '../app/src/pcb/read-board';
import { busyBoard } from '../app/src/pcb/test-boards';
import { compare, type Row } from './harness';

export function pcbBench(): Row[] {
  const text = busyBoard();
  const set = readBoard([{ name: 'busy-F_Cu.gbr', text }]);
  if (set.problems.length) throw new Error(set.problems[0].message);
  const opts = { expose: ['copper-top'], pitchUm: { x: 50, y: 50 }, threshold: 0.5, windowMm: { x0: 0, y0: 0, x1: 100, y1: 80 } };
  const cells = new Float32Array(2000 * 1600);
  return compare('B3 Gerber to cells, 100 x 80 mm busy copper at 50 um (2000x1600)', {
    name: 'baseline: one pass writing every cell',
    run: () => {
      for (let i = 0; i < cells.length; i++) cells[i] = i & 1;
    },
  }, [
    { name: 'read the Gerber (parse and plot)', run: () => void readBoard([{ name: 'busy-F_Cu.gbr', text }]) },
    { name: 'rasterise by coverage', run: () => {
      const r = rasteriseBoard(set, opts);
      if (r.cols !== 2000 || r.rows !== 1600) throw new Error(`${r.cols} x ${r.rows}`);
    } },
  ], 3);
}
