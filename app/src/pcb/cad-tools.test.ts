// Issue 40: board sets as each CAD tool writes them (hand-written in e2e/fixtures/pcb/cad-tools/, modelled on
// the tools' own output): the window comes from the outline, zero-width outlines are drawn, a file's head beats
// its name, numbered files find their top copper, block apertures are refused by name, impossible arcs are said.
import { mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { boardArtwork, boardSrc, boardWindow } from './board-artwork';
import { HAIRLINE_MM } from './plot-to-artwork';
import { agreement, gerbvCells, hasGerbv } from './gerbv-reference';
import { rasteriseBoard } from './rasterise';
import { readBoard } from './read-board';
import { at, gerber } from './test-boards';

const DIR = join(import.meta.dirname, '../../../e2e/fixtures/pcb/cad-tools');
const set = (tool: string) => readdirSync(join(DIR, tool)).sort().map((name) => ({ name, text: readFileSync(join(DIR, tool, name), 'utf8') }));
const size = (b: { x0: number; y0: number; x1: number; y1: number }) => [+(b.x1 - b.x0).toFixed(4), +(b.y1 - b.y0).toFixed(4)];
const kinds = (tool: string) => Object.fromEntries(readBoard(set(tool)).layers.map((l) => [l.file, l.kind]));

describe('the board’s window: its outline, never a drawing', () => {
  it('EasyEDA Pro: the drill drawing and document layers, far off the board, leave its 33.4 × 32.0 mm alone', () => {
    const board = boardArtwork(boardSrc(set('easyeda-pro')));
    expect(size(board.windowMm)).toEqual([33.4, 32]);
    expect(board.windowMm.x0).toBeCloseTo(0, 9);
    expect(kinds('easyeda-pro')).toMatchObject({ 'Gerber_DrillDrawingLayer.GDD': 'other', 'Gerber_DocumentLayer.GDL': 'other', 'Gerber_BoardOutlineLayer.GKO': 'outline', 'Gerber_TopLayer.GTL': 'copper-top' });
  });

  it('DipTrace: of two outlines, the board’s (the smallest that holds the copper), not the dimension layer’s', () => {
    expect(size(boardArtwork(boardSrc(set('diptrace'))).windowMm)).toEqual([31.2, 48]);
  });

  it('with no outline, what may be exposed, never a drawing', () => {
    const files = set('easyeda-pro').filter((f) => !f.name.includes('Outline'));
    const window = boardWindow(readBoard(files));
    const copper = readBoard(files).layers.find((l) => l.kind === 'copper-top')!.boundsMm;
    expect(window).toEqual(copper); // the drill file's holes lie inside the copper's pads
  });

  it('an outline that does not hold the copper (a milling layer) leaves the window to one that does', () => {
    const copper = gerber(`%ADD10C,1*%\nD10*\n${at(2, 2)}D03*\n${at(18, 8)}D03*`);
    const rect = (x0: number, y0: number, x1: number, y1: number) => gerber(`%ADD10C,0.1*%\nD10*\n${at(x0, y0)}D02*\n${at(x1, y0)}D01*\n${at(x1, y1)}D01*\n${at(x0, y1)}D01*\n${at(x0, y0)}D01*`);
    const read = readBoard([
      { name: 'b-F_Cu.gbr', text: copper },
      { name: 'b-Edge_Cuts.gbr', text: rect(0, 0, 20, 10) },
      { name: 'b.gko', text: rect(5, 4, 7, 6) },
    ]);
    expect(read.layers.map((l) => l.kind)).toEqual(['copper-top', 'outline', 'outline']);
    expect(size(boardWindow(read))).toEqual([20, 10]);
  });
});

describe('zero-width draws (Eagle’s %ADD10C,0.0000*%)', () => {
  const eagle = set('eagle');

  it('draw the outline, which sets the window by its centre line: the board’s true corner', () => {
    const board = boardArtwork(boardSrc(eagle));
    expect(board.set.problems.filter((p) => p.file === 'blinky.GKO')).toEqual([]);
    const outline = board.set.layers.find((l) => l.file === 'blinky.GKO')!;
    expect(outline.kind).toBe('outline');
    expect(outline.notes).toContain(`1 draw with a zero-width aperture, drawn ${HAIRLINE_MM} mm wide`);
    expect([board.windowMm.x0, board.windowMm.y0]).toEqual([0, 0]);
    expect(size(board.windowMm)).toEqual([38.1, 25.4]); // 1.5 × 1 inch
  });

  it('expose a cutting guide, and the silk’s hairline, which the board says', () => {
    const read = readBoard(eagle);
    const guide = rasteriseBoard(read, { expose: ['outline'], pitchUm: { x: 50, y: 50 }, windowMm: { x0: -1, y0: -1, x1: 40, y1: 27 } });
    // A column of cells through the left edge: the line is HAIRLINE_MM (2 cells) wide there, at mid-height.
    const row = Math.round((27 - 12.7) / 0.05);
    const lit = Array.from({ length: 60 }, (_, c) => guide.cells[row * guide.cols + c]).reduce((a, v) => a + v, 0);
    expect(lit).toBe(2);
    expect(read.problems).toEqual([{ file: 'blinky.GTO', message: `1 draw with a zero-width aperture, drawn ${HAIRLINE_MM} mm wide` }]);
    // On the board's own window (the outline's centre line), the line's inner half: one cell along each edge.
    const board = boardArtwork(boardSrc(eagle));
    const look = { layers: eagle.map((f) => ({ kind: f.name.endsWith('.GKO') ? ('outline' as const) : ('other' as const), expose: f.name.endsWith('.GKO') })), drillClear: 'none' as const, marks: [] };
    const v = board.cover(762, 508, look); // 1.5 × 1 in at 50 µm
    const mid = 254 * 762;
    expect([v.values[mid], v.values[mid + 1], v.values[mid + 760], v.values[mid + 761]]).toEqual([0, 255, 255, 0]);
  });
});

describe('what a file says of itself beats its name', () => {
  it('%LN: "top.grb" whose head says top silk is silk; "bottom.grb" saying bottom mask is the mask', () => {
    expect(kinds('header-wins')).toEqual({ 'top.grb': 'silk-top', 'layer1.grb': 'copper-top', 'bottom.grb': 'mask-bottom' });
  });

  it('EasyEDA’s "G04 Layer:" names, paste mask included', () => {
    const named = (layer: string, file: string) => readBoard([{ name: file, text: `G04 EasyEDA Pro v2.1*\nG04 Layer: ${layer}*\n` + gerber(`%ADD10C,1*%\nD10*\n${at(0, 0)}D03*`) }]).layers[0].kind;
    expect(named('TopPasteMaskLayer', 'Gerber_TopLayer.GTL')).toBe('paste-top');
    expect(named('BottomSilkscreenLayer', 'top.gbr')).toBe('silk-bottom');
    expect(named('TopSolderMaskLayer', 'x.gbr')).toBe('mask-top');
    expect(named('BottomLayer', 'x.gbr')).toBe('copper-bottom');
    expect(named('DrillDrawingLayer', 'Gerber_TopLayer.GTL')).toBe('other');
  });
});

describe('numbered files that say nothing', () => {
  it('take for the top copper the one with pads where no hole is drilled, the other for the bottom, and say so', () => {
    const read = readBoard(set('numbered'));
    expect(read.layers.map((l) => [l.file, l.kind, l.kindFrom])).toEqual([
      ['f01.gbr', 'copper-bottom', 'content'],
      ['f02.gbr', 'copper-top', 'content'],
      ['f03.drl', 'drill', 'content'],
    ]);
    expect(read.problems).toEqual([{ file: 'f02.gbr', message: expect.stringMatching(/^taken for the top copper from what it draws: 8 pads without a hole.*f01\.gbr 0/) }]);
  });

  it('with nothing to tell them apart, keep the first and say it is only a guess', () => {
    const files = set('numbered');
    const same = [{ name: 'f01.gbr', text: files[0].text }, { name: 'f02.gbr', text: files[0].text }];
    const read = readBoard(same);
    expect(read.layers.map((l) => l.kind)).toEqual(['copper-top', 'copper-bottom']);
    expect(read.problems[0].message).toMatch(/only because it comes first.*check which is the top/);
  });
});

describe('block apertures (%AB)', () => {
  // gerbv 2.9 does not read %AB either (it draws the block's contents once, where they are written): its referee
  // is the same artwork written out flat, each block's pads and track moved to where it is flashed.
  const FLAT = gerber(['%ADD10C,0.5*%', '%ADD11R,1.0X1.0*%', ...[5, 10].flatMap((y) => ['D11*', `${at(5, y)}D03*`, `${at(7, y)}D03*`, 'D10*', `${at(5, y)}D02*`, `${at(7, y)}D01*`])].join('\n'));

  it('are drawn where each is flashed, as gerbv draws the same artwork written flat', () => {
    const read = readBoard(set('block-aperture'));
    expect(read.problems).toEqual([]);
    const copper = read.layers.find((l) => l.file === 'panel-F_Cu.gbr')!;
    expect(copper.kind).toBe('copper-top');
    expect(copper.boundsMm).toEqual({ x0: 4.5, y0: 4.5, x1: 7.5, y1: 10.5 }); // two blocks, each two pads and a track
    expect(hasGerbv(), 'gerbv is not installed: apt-get install gerbv').toBe(true);
    const [x0, y0, p, cols, rows] = [0, 0, 0.05, 300, 300];
    const ours = rasteriseBoard(read, { expose: ['panel-F_Cu.gbr'], pitchUm: { x: 50, y: 50 }, windowMm: { x0, y0, x1: x0 + cols * p, y1: y0 + rows * p } });
    const dir = mkdtempSync(join(tmpdir(), 'flat-'));
    writeFileSync(join(dir, 'flat.gbr'), FLAT);
    const theirs = gerbvCells(join(dir, 'flat.gbr'), { cols, rows, x0, y0, pitchMm: p });
    rmSync(dir, { recursive: true });
    const a = agreement(ours.cells, theirs, cols, rows);
    expect(theirs.reduce((n, v) => n + v, 0)).toBeGreaterThan(1000); // gerbv drew the blocks
    expect(a.interiorAgree).toBe(a.interior); // every difference lies on an edge
    expect(a.allAgree / a.all).toBeGreaterThan(0.99);
  });

  it('a block inside a block is refused by name, never a throw', () => {
    const nested = gerber(`%ADD10C,1*%\n%ABD12*%\n%ABD13*%\nD10*\n${at(0, 0)}D03*\n%AB*%\n%AB*%\nD12*\n${at(5, 5)}D03*`);
    const read = readBoard([{ name: 'x-F_Cu.gbr', text: nested }]);
    expect(read.layers).toEqual([]);
    expect(read.problems[0].message).toMatch(/block aperture \(%AB\) inside another is not supported/);
  });
});

describe('an impossible arc', () => {
  const region = (endY: number) => gerber(`%ADD10C,0.1*%\nG75*\nG36*\n${at(0, 0)}D02*\nG01*\n${at(10, 0)}D01*\nG03*\n${at(0, endY)}I-10000000J0D01*\nG01*\n${at(0, 0)}D01*\nG37*`);

  it('in a region is drawn as written, and said', () => {
    const read = readBoard([{ name: 'x-F_Cu.gbr', text: region(11) }]);
    expect(read.layers).toHaveLength(1);
    expect(read.problems).toEqual([{ file: 'x-F_Cu.gbr', message: expect.stringMatching(/^1 impossible arc, whose end lies more than 0\.01 mm/) }]);
  });

  it('is not said of a true one, nor of one its file’s coordinates round (Protel’s %FSLAX23: 0.001 in)', () => {
    expect(readBoard([{ name: 'x-F_Cu.gbr', text: region(10) }]).problems).toEqual([]);
    // Centre (0, 0), start (1, 0) in, end (0, 1.001) in: 25 µm off its circle, within three steps of 0.001 in.
    const protel = `%FSLAX23Y23*%\n%MOIN*%\n%ADD10C,0.010*%\nG75*\nD10*\nX1000Y0D02*\nG03X0Y1001I-1000J0D01*\nM02*\n`;
    expect(readBoard([{ name: 'x.GTL', text: protel }]).problems).toEqual([]);
    const far = protel.replace('Y1001I', 'Y1004I'); // 0.004 in, past three steps
    expect(readBoard([{ name: 'x.GTL', text: far }]).problems.map((p) => p.message)).toEqual([expect.stringMatching(/^1 impossible arc, whose end lies more than 0\.076 mm/)]);
  });
});

describe('drill dots', () => {
  it('are as wide as their holes, up to 0.4 mm', () => {
    const copper = gerber(`%ADD10C,1*%\nD10*\n${at(1, 1)}D03*\n${at(4, 1)}D03*`);
    const drill = 'M48\nMETRIC\nT1C0.2\nT2C1.0\n%\nT1\nX1.0Y1.0\nT2\nX4.0Y1.0\nM30\n';
    const read = readBoard([{ name: 'b-F_Cu.gbr', text: copper }, { name: 'b.drl', text: drill }]);
    const pitch = 10;
    const r = rasteriseBoard(read, { expose: ['copper-top'], pitchUm: { x: pitch, y: pitch }, drillClear: 'unexposed-dot' });
    const bare = (cx: number) => {
      const row = Math.floor((r.windowMm.y1 - 1) / (pitch / 1000));
      let n = 0;
      for (let c = 0; c < r.cols; c++) {
        const x = r.windowMm.x0 + (c + 0.5) * (pitch / 1000);
        if (Math.abs(x - cx) < 0.5 && !r.cells[row * r.cols + c]) n++;
      }
      return (n * pitch) / 1000;
    };
    expect(bare(1)).toBeCloseTo(0.2, 2);
    expect(bare(4)).toBeCloseTo(0.4, 2);
  });
});
