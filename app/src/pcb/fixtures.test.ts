// The hand-written demo board in e2e/fixtures/pcb/ reads cleanly, kinds and all: the studio's tests can rely on it.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { rasteriseBoard } from './rasterise';
import { readBoard } from './read-board';

const DIR = join(import.meta.dirname, '../../../e2e/fixtures/pcb');

describe('the demo board for end-to-end tests', () => {
  it('reads as five layers of five kinds, no problems, on a 30 × 20 mm outline', () => {
    const files = readdirSync(DIR).filter((f) => f.startsWith('demo-')).map((name) => ({ name, text: readFileSync(join(DIR, name), 'utf8') }));
    const set = readBoard(files);
    expect(set.problems).toEqual([]);
    expect(Object.fromEntries(set.layers.map((l) => [l.file, l.kind]))).toEqual({
      'demo-B_Cu.gbr': 'copper-bottom',
      'demo-Edge_Cuts.gbr': 'outline',
      'demo-F_Cu.gbr': 'copper-top',
      'demo-F_Mask.gbr': 'mask-top',
      'demo-PTH.drl': 'drill',
    });
    expect(set.layers.find((l) => l.kind === 'drill')!.holes).toHaveLength(5);
    const r = rasteriseBoard(set, { expose: ['copper-top'], pitchUm: { x: 50, y: 50 }, threshold: 0.5, drillClear: 'unexposed-dot' });
    expect([r.cols, r.rows]).toEqual([602, 402]); // the outline's 0.1 mm line reaches 0.05 mm past the board
    expect(r.cells.reduce((a, c) => a + c, 0)).toBeGreaterThan(20000);
  });
});
