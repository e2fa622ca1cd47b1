// A board's files picked together: one object at its window's size, named after the board, kinds guessed, bad files named.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it, vi } from 'vitest';
import { inThreadPort } from '../../work/in-thread.fixture';
import { artworkObject, boardName, importBoard, isBoardPick } from './import-artwork';

// The board is read by the work worker: here, in the same thread.
vi.mock('../../work/work-client', async (original) => ({ ...(await original<typeof import('../../work/work-client')>()), spawnWorker: () => inThreadPort() }));

const DIR = join(import.meta.dirname, '../../../../e2e/fixtures/pcb');
const demo = () => readdirSync(DIR).filter((f) => f.startsWith('demo-')).sort().map((name) => new File([readFileSync(join(DIR, name), 'utf8')], name));

describe('which picks are a board', () => {
  it('several files, or one that is no picture or drawing', () => {
    expect(isBoardPick(demo())).toBe(true);
    expect(isBoardPick([new File(['G04*'], 'top.gtl')])).toBe(true);
    expect(isBoardPick([new File(['G04*'], 'board-F_Cu.gbr', { type: 'image/x-gimp-gbr' })])).toBe(true); // as Chromium on Linux types it
    expect(isBoardPick([new File([''], 'logo.png', { type: 'image/png' })])).toBe(false);
    expect(isBoardPick([new File([''], 'drawing.svg')])).toBe(false);
  });

  it('is named by what its files share', () => {
    expect(boardName(['amp-F_Cu.gbr', 'amp-B_Cu.gbr', 'amp-PTH.drl'])).toBe('amp');
    expect(boardName(['top.gtl', 'bottom.gbl'])).toBe('top.gtl');
    expect(boardName(['only.gbr'])).toBe('only.gbr');
  });
});

describe('a board imported', () => {
  it('is one object at the window of all its layers, top copper exposed, the unreadable file named', async () => {
    const files = [...demo(), new File(['just some notes'], 'demo-notes.gbr')];
    const a = await importBoard(files);
    expect(a.kind).toBe('board');
    expect(a.name).toBe('demo');
    expect(a.sizeMm!.x).toBeCloseTo(30, 6); // the outline's centre line
    expect(a.sizeMm!.y).toBeCloseTo(20, 6);
    expect(a.problems).toEqual([{ file: 'demo-notes.gbr', messages: [expect.stringMatching(/^not a Gerber or Excellon drill file/)] }]);
    expect(a.board!.layers.map((l) => [l.file, l.kind, l.expose])).toEqual([
      ['demo-B_Cu.gbr', 'copper-bottom', false],
      ['demo-Edge_Cuts.gbr', 'outline', false],
      ['demo-F_Cu.gbr', 'copper-top', true],
      ['demo-F_Mask.gbr', 'mask-top', false],
      ['demo-PTH.drl', 'drill', false],
      ['demo-notes.gbr', 'other', false],
    ]);
    expect(artworkObject(a, { x: 1, y: 2, w: 602, h: 402 })).toMatchObject({ kind: 'board', name: 'demo', halftone: 'threshold', threshold: 50, drillClear: 'unexposed-dot', marks: [] });
  });

  it('that draws nothing is refused, saying why, one entry a file', async () => {
    await expect(importBoard([new File(['hello'], 'notes.txt')])).rejects.toThrow(/notes\.txt/);
    const e = await importBoard([new File(['hello'], 'notes.txt'), new File([''], 'empty.gbr')]).catch((e: unknown) => e);
    expect((e as { problems: unknown }).problems).toEqual([
      { file: 'notes.txt', messages: [expect.stringMatching(/^not a Gerber/)] },
      { file: 'empty.gbr', messages: ['the file is empty'] },
    ]);
  });

  it('whose files say nothing of copper: the one that draws as copper does is taken for it, exposed, and remembered', async () => {
    const copper = readFileSync(join(DIR, 'demo-F_Cu.gbr'), 'utf8').replace(/%TF\.FileFunction[^\n]*\n/, '');
    const a = await importBoard([new File([readFileSync(join(DIR, 'demo-Edge_Cuts.gbr'), 'utf8')], 'edge.gbr'), new File([copper], 'artwork_1.grb')]);
    expect(a.board!.layers.map((l) => [l.file, l.kind, l.expose])).toEqual([
      ['edge.gbr', 'outline', false],
      ['artwork_1.grb', expect.any(String), true],
    ]);
  });
});
