// The double-sided workflow's arithmetic: the bottom side, one side a job, marks on the bed, the job origin at the head.
import { describe, expect, it } from 'vitest';
import { bottomSide, hasCopper, markOnBed, newBoardFields, onlySide, originAtHead, sideInJob, sideOf, twoSidedBoards } from './board-object';
import { exposes, type BoardLayerKind, type BoardObject } from './objects';

const KINDS = (['copper-top', 'copper-bottom', 'outline', 'drill'] as const).map((kind) => ({ file: `demo-${kind}.gbr`, kind }));
const board = (more: Partial<BoardObject> = {}): BoardObject => ({
  id: 1, kind: 'board', name: 'demo', src: 'data:', halftone: 'threshold', threshold: 50, tone: { invert: false, contrast: 0, gamma: 1 },
  x: 100, y: 50, w: 300, h: 200, ...newBoardFields(KINDS), ...more,
});
const WINDOW = { width: 30000, height: 20000 }; // 30 × 20 mm over 300 × 200 cells of 100 µm

describe('a new board', () => {
  it('exposes its top copper and leaves a dot at each hole unexposed', () => {
    expect(newBoardFields(KINDS)).toMatchObject({ layers: [{ kind: 'copper-top', expose: true }, { kind: 'copper-bottom', expose: false }, { kind: 'outline', expose: false }, { kind: 'drill', expose: false }], drillClear: 'unexposed-dot', marks: [] });
    expect(newBoardFields(KINDS.slice(1, 3)).layers.map((l) => l.expose)).toEqual([true, false]);
    expect(newBoardFields(KINDS.slice(1, 3)).drillClear).toBe('none');
  });

  it('with no copper, exposes the first file read that is artwork, not a drill, an outline or an unreadable file', () => {
    const f = (file: string, kind: BoardLayerKind, from = 'name') => ({ file, kind, from });
    const noCopper = [f('notes.gbr', 'other', 'unread'), f('holes.ncd', 'drill', 'content'), f('edge.gbr', 'outline'), f('Assembly.gdo', 'other'), f('art.grb', 'other', 'none')];
    expect(newBoardFields(noCopper).layers.map((l) => l.expose)).toEqual([false, false, false, true, false]);
    expect(newBoardFields(noCopper.slice(0, 3)).layers.map((l) => l.expose)).toEqual([false, false, true]);
    expect(newBoardFields(noCopper.slice(0, 2)).layers.map((l) => l.expose)).toEqual([false, false]);
    expect(newBoardFields(noCopper).copperGuessed).toBeUndefined();
    expect(hasCopper(newBoardFields(noCopper))).toBe(false);
  });

  it('remembers a copper layer taken from what the file draws, to say so', () => {
    const b = newBoardFields([{ file: 'artwork_1.grb', kind: 'copper-top', from: 'content' }, { file: 'holes.ncd', kind: 'drill', from: 'content' }]);
    expect(b).toMatchObject({ layers: [{ expose: true }, { expose: false }], copperGuessed: 'artwork_1.grb', drillClear: 'unexposed-dot' });
    expect(hasCopper(b)).toBe(true);
  });

  it('names the copper it exposes when both sides were taken from what they draw (numbered files)', () => {
    const b = newBoardFields([{ file: 'f01.gbr', kind: 'copper-bottom', from: 'content' }, { file: 'f02.gbr', kind: 'copper-top', from: 'content' }]);
    expect(b).toMatchObject({ layers: [{ expose: false }, { expose: true }], copperGuessed: 'f02.gbr' });
  });
});

describe('a side left out of the job', () => {
  it('exposes nothing until taken back', () => {
    expect(exposes(board())).toBe(true);
    expect(exposes(board({ leftOut: true }))).toBe(false);
  });
});

describe('the bottom side', () => {
  it('turned over about the middle: the same box, mirrored, exposing the bottom copper', () => {
    const b = bottomSide(board(), 'left-right', 'centre');
    expect(b).toMatchObject({ x: 100, y: 50, w: 300, h: 200, mirror: true, turn: 0, name: 'demo (bottom)' });
    expect(b.layers.map((l) => l.expose)).toEqual([false, true, false, false]);
    expect('id' in b).toBe(false);
  });

  it('starts left out of the job: the top side is exposed first, and one side at a time', () => {
    expect(bottomSide(board(), 'left-right', 'centre').leftOut).toBe(true);
    expect(bottomSide(board({ leftOut: false }), 'top-bottom', 'end').leftOut).toBe(true);
  });

  it('turned over about an edge: beside the board on that side', () => {
    expect(bottomSide(board(), 'left-right', 'start')).toMatchObject({ x: -200, y: 50 });
    expect(bottomSide(board(), 'left-right', 'end')).toMatchObject({ x: 400, y: 50 });
    expect(bottomSide(board(), 'top-bottom', 'end')).toMatchObject({ x: 100, y: 250, mirror: true, turn: 2 });
  });
});

describe('one side a job', () => {
  const top = board();
  const bottom = { ...bottomSide(top, 'left-right', 'centre'), id: 2 } as BoardObject;
  const other = board({ id: 3, src: 'data:other', name: 'other' });

  it('knows a side by the layers it exposes, else by its mirror', () => {
    expect([sideOf(top), sideOf(bottom)]).toEqual(['top', 'bottom']);
    const bare = (mirror: boolean) => board({ mirror, layers: KINDS.map(({ file, kind }) => ({ file, kind, expose: kind === 'outline' })) });
    expect([sideOf(bare(false)), sideOf(bare(true))]).toEqual(['top', 'bottom']);
    expect(sideOf(board({ layers: [{ file: 'b-mask.gbr', kind: 'mask-bottom', expose: true }] }))).toBe('bottom');
  });

  it('finds the boards placed as two sides, and which side the job exposes', () => {
    expect(twoSidedBoards([top, other])).toEqual([]);
    const [b] = twoSidedBoards([top, other, bottom]);
    expect(b).toEqual({ name: 'demo', sides: [{ id: 1, name: 'demo', side: 'top', inJob: true }, { id: 2, name: 'demo (bottom)', side: 'bottom', inJob: false }] });
    expect(sideInJob(b)).toBe('the top side of board demo');
    expect(sideInJob(twoSidedBoards([top, { ...bottom, leftOut: false }])[0])).toBeNull(); // both: no one side to name
  });

  it('takes one side into the job and leaves the others out', () => {
    const [b] = twoSidedBoards([top, bottom]);
    expect(onlySide(b, 2)).toEqual(new Map([[1, { leftOut: true }], [2, { leftOut: false }]]));
    expect(onlySide(b, 1)).toEqual(new Map([[1, { leftOut: false }], [2, { leftOut: true }]]));
  });
});

describe('a registration mark on the bed', () => {
  it('lies where its mm from the lower left corner put it, mirrored and turned with the object', () => {
    const mark = { x: 3, y: 2 };
    expect(markOnBed(board(), mark, WINDOW)).toEqual({ x: 130, y: 230 });
    expect(markOnBed(board({ mirror: true }), mark, WINDOW)).toEqual({ x: 370, y: 230 });
    // A quarter turn clockwise: the box is 200 × 300 and the lower left corner comes to the top left.
    expect(markOnBed(board({ turn: 1, w: 200, h: 300 }), { x: 0, y: 0 }, WINDOW)).toEqual({ x: 100, y: 50 });
    expect(markOnBed(board({ turn: 2 }), { x: 0, y: 0 }, WINDOW)).toEqual({ x: 400, y: 50 });
    expect(markOnBed(board({ turn: 3, w: 200, h: 300 }), { x: 0, y: 0 }, WINDOW)).toEqual({ x: 300, y: 350 });
  });

  it('comes under the head when the job origin is set there', () => {
    const o = board();
    const to = originAtHead(o, { x: 3, y: 2 }, WINDOW, [20_000, 31_000, 0], { x: 100, y: 100 });
    expect(markOnBed({ ...o, ...to }, { x: 3, y: 2 }, WINDOW)).toEqual({ x: 200, y: 310 });
  });
});

describe('what the studio keeps of app/src/pcb, which loads on demand', () => {
  it('names the same layer kinds and embeds boards the same way', async () => {
    const pcb = await import('../../pcb');
    const { BOARD_LAYER_KINDS } = await import('./objects');
    expect(BOARD_LAYER_KINDS).toEqual(pcb.LAYER_KINDS);
    const file = await import('node:fs').then((fs) => fs.readFileSync(new URL('../../project/project-file.ts', import.meta.url), 'utf8'));
    expect(file).toContain(`'${pcb.BOARD_SRC_PREFIX}'`);
  });
});
