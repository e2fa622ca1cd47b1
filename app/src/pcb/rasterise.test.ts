import { describe, expect, it } from 'vitest';
import { LINES_PER_CELL, rasteriseBoard, type RasteriseOptions } from './rasterise';
import { at, boardOf, count, coveredArea, gerber, picture } from './test-boards';
import { readBoard, type BoardSet } from './read-board';

const window = (x1: number, y1: number) => ({ x0: 0, y0: 0, x1, y1 });
const raster = (set: BoardSet, win: { x0: number; y0: number; x1: number; y1: number }, pitchUm = 100, more: Partial<RasteriseOptions> = {}) =>
  rasteriseBoard(set, { expose: set.layers.map((l) => l.file), pitchUm: { x: pitchUm, y: pitchUm }, threshold: 0.5, windowMm: win, ...more });

// The error bound the rasteriser promises for one horizontal edge or corner in a cell (see rasterise.ts).
const Y_BOUND = 1 / (2 * LINES_PER_CELL);

describe('standard apertures', () => {
  it('flashes a rectangle on the grid as whole cells, covered exactly', () => {
    const set = boardOf(gerber(`%ADD10R,0.3X0.2*%\nD10*\n${at(0.25, 0.2)}D03*`));
    const r = raster(set, window(0.6, 0.4));
    expect(picture(r)).toEqual(['......', '.###..', '.###..', '......']);
    for (let i = 0; i < r.coverage.length; i++) expect(r.coverage[i]).toBeCloseTo(r.cells[i], 4);
    const b = set.layers[0].boundsMm;
    expect([b.x0, b.y0, b.x1, b.y1].map((v) => +v.toFixed(9))).toEqual([0.1, 0.1, 0.4, 0.3]);
  });

  it('covers half of each edge cell of a rectangle half a cell off the grid, exactly across and within its bound down', () => {
    const r = raster(boardOf(gerber(`%ADD10R,0.3X0.3*%\nD10*\n${at(0.3, 0.3)}D03*`)), window(0.6, 0.6));
    // x from 0.15 to 0.45: columns 1 and 4 are half covered; likewise rows 1 and 4.
    expect(r.coverage[2 * 6 + 1]).toBeCloseTo(0.5, 4);
    expect(r.coverage[2 * 6 + 4]).toBeCloseTo(0.5, 4);
    expect(Math.abs(r.coverage[1 * 6 + 2] - 0.5)).toBeLessThanOrEqual(Y_BOUND + 1e-6); // coverage is a float32
    expect(r.coverage[2 * 6 + 2]).toBeCloseTo(1, 4);
    expect(coveredArea(r)).toBeCloseTo(0.09, 3);
  });

  it('flashes a circle with the area of a circle', () => {
    const r = raster(boardOf(gerber(`%ADD10C,0.5*%\nD10*\n${at(0.5, 0.5)}D03*`)), window(1, 1), 50);
    expect(coveredArea(r) / (Math.PI * 0.25 * 0.25)).toBeCloseTo(1, 3);
    expect(count(r)).toBeGreaterThan(70); // π r² over the cell is 78.5 cells
    expect(count(r)).toBeLessThan(87);
  });

  it('flashes an obround either way round as a rectangle with round ends', () => {
    const area = 0.4 * 0.2 + Math.PI * 0.1 * 0.1;
    for (const size of ['0.6X0.2', '0.2X0.6']) {
      const r = raster(boardOf(gerber(`%ADD10O,${size}*%\nD10*\n${at(0.5, 0.5)}D03*`)), window(1, 1), 50);
      expect(coveredArea(r) / area).toBeCloseTo(1, 3);
    }
  });

  it('flashes regular polygons, rotated as asked', () => {
    const hexagon = raster(boardOf(gerber(`%ADD10P,1.0X6*%\nD10*\n${at(0.5, 0.5)}D03*`)), window(1, 1), 50);
    expect(coveredArea(hexagon) / ((3 * Math.sqrt(3)) / 2 / 4)).toBeCloseTo(1, 3);
    // Four vertices turned 45°: an upright square of side 1/√2, centred on (0.5, 0.5).
    const square = raster(boardOf(gerber(`%ADD10P,1.0X4X45*%\nD10*\n${at(0.5, 0.5)}D03*`)), window(1, 1), 50);
    expect(coveredArea(square)).toBeCloseTo(0.5, 3);
    expect(square.cells[0]).toBe(0);
    expect(square.cells[10 * 20 + 10]).toBe(1);
  });

  it('leaves an aperture’s hole open without erasing what lies under it', () => {
    const ring = raster(boardOf(gerber(`%ADD10C,1.0X0.4*%\nD10*\n${at(0.5, 0.5)}D03*`)), window(1, 1), 50);
    expect(coveredArea(ring) / (Math.PI * (0.25 - 0.04))).toBeCloseTo(1, 3);
    expect(ring.cells[10 * 20 + 10]).toBe(0);
    const over = raster(boardOf(gerber(`%ADD10R,1X1*%\n%ADD11C,1.0X0.4*%\nD10*\n${at(0.5, 0.5)}D03*\nD11*\n${at(0.5, 0.5)}D03*`)), window(1, 1), 50);
    expect(count(over)).toBe(400);
  });
});

describe('aperture macros', () => {
  it('builds a macro of circles and an outline, an exposure-off primitive cutting the macro only', () => {
    const body = `%AMTARGET*
0 a disc with a clear centre and a bar to its right*
1,1,0.8,0,0*
1,0,0.3,0,0*
4,1,4,0.5,-0.05,0.9,-0.05,0.9,0.05,0.5,0.05,0.5,-0.05,0*%
%ADD10TARGET*%
%ADD11R,0.2X0.2*%
D11*
${at(1, 1)}D03*
D10*
${at(1, 1)}D03*`;
    const r = raster(boardOf(gerber(body)), window(2, 2), 50);
    // The square under the flash is not erased by the macro's clear centre: the macro cuts itself only.
    expect(coveredArea(r) / (Math.PI * (0.16 - 0.0225) + 0.04 + 0.04)).toBeCloseTo(1, 3);
    expect(r.cells[20 * 40 + 20]).toBe(1); // under the square
    expect(r.cells[19 * 40 + 22]).toBe(0); // in the clear centre, off the square
    expect(r.cells[19 * 40 + 37]).toBe(1); // on the bar
  });

  it('takes parameters and arithmetic, and turns a centre line', () => {
    const body = `%AMBAR*
$3=$1x2*
21,1,$3,$2,0,0,45*%
%ADD10BAR,0.25X0.1*%
D10*
${at(1, 1)}D03*`;
    const r = raster(boardOf(gerber(body)), window(2, 2), 50);
    expect(coveredArea(r)).toBeCloseTo(0.5 * 0.1, 3);
    expect(r.cells[20 * 40 + 20]).toBe(1);
    expect(r.cells[17 * 40 + 23]).toBe(1); // up and to the right along the 45° bar
    expect(r.cells[17 * 40 + 17]).toBe(0);
  });
});

describe('draws and regions', () => {
  it('draws a trace with round ends', () => {
    const r = raster(boardOf(gerber(`%ADD10C,0.2*%\nD10*\n${at(0.5, 0.5)}D02*\n${at(1.5, 0.5)}D01*`)), window(2, 1), 50);
    expect(coveredArea(r) / (1 * 0.2 + Math.PI * 0.01)).toBeCloseTo(1, 3);
  });

  it('fills a region bounded by lines and a counter-clockwise multi-quadrant arc', () => {
    // A "D": the unit square with a half disc of radius 0.5 on its right.
    const body = `G75*
G36*
${at(0, 0)}D02*
G01*
${at(1, 0)}D01*
G03*
${at(1, 1)}I0J${500000}D01*
G01*
${at(0, 1)}D01*
${at(0, 0)}D01*
G37*`;
    const r = raster(boardOf(gerber(body)), window(2, 1), 50);
    expect(coveredArea(r) / (1 + Math.PI / 8)).toBeCloseTo(1, 3);
    expect(r.cells[10 * 40 + 29]).toBe(1); // inside the half disc
    expect(r.cells[1 * 40 + 29]).toBe(0); // above its arc
  });

  it('fills a region with a round hole cut in with clockwise arcs', () => {
    const body = `G75*
G36*
${at(0, 0)}D02*
G01*
${at(2, 0)}D01*
${at(2, 2)}D01*
${at(0, 2)}D01*
${at(0, 1)}D01*
${at(0.5, 1)}D01*
G02*
${at(1.5, 1)}I500000J0D01*
${at(0.5, 1)}I-500000J0D01*
G01*
${at(0, 1)}D01*
${at(0, 0)}D01*
G37*`;
    const r = raster(boardOf(gerber(body)), window(2, 2), 50);
    expect(coveredArea(r) / (4 - Math.PI / 4)).toBeCloseTo(1, 3);
    expect(r.cells[20 * 40 + 20]).toBe(0);
    expect(r.cells[2 * 40 + 2]).toBe(1);
  });
});

describe('polarity and step and repeat', () => {
  it('clears with LPC what was drawn before, and draws again after LPD', () => {
    const body = `%ADD10R,2X2*%
%ADD11R,1X1*%
%ADD12C,0.2*%
D10*
${at(1, 1)}D03*
%LPC*%
D11*
${at(1, 1)}D03*
%LPD*%
D12*
${at(1, 1)}D03*`;
    const r = raster(boardOf(gerber(body)), window(2, 2));
    const rows = picture(r);
    expect(rows[4]).toBe('####################');
    expect(rows[5]).toBe('#####..........#####');
    expect(rows[9]).toBe('#####....##....#####');
    expect(rows[10]).toBe('#####....##....#####');
    expect(count(r)).toBe(400 - 100 + 4);
  });

  it('repeats a block with SR, and a clear part of it clears the copies before it', () => {
    const body = `%ADD10R,0.2X0.2*%
%ADD11R,0.1X0.1*%
%SRX3Y2I1.0J0.5*%
D10*
${at(0.1, 0.1)}D03*
%SR*%
${at(1.1, 1.1)}D03*`;
    const r = raster(boardOf(gerber(body)), window(2.4, 1.4));
    const expected = new Set<string>();
    for (const [x, y] of [0, 1, 2].flatMap((i) => [0, 1].map((j) => [i, j * 5]))) {
      for (const [dx, dy] of [[0, 0], [1, 0], [0, 1], [1, 1]]) expected.add(`${10 * x + dx},${y + dy}`);
    }
    for (const [dx, dy] of [[0, 0], [1, 0], [0, 1], [1, 1]]) expected.add(`${10 + dx},${10 + dy}`); // after the repeat ends
    const got = new Set<string>();
    r.cells.forEach((v, i) => v && got.add(`${i % r.cols},${r.rows - 1 - Math.floor(i / r.cols)}`));
    expect(got).toEqual(expected);
  });

  it('applies clear polarity inside a repeated block to every copy, in order', () => {
    const body = `%ADD10R,0.4X0.4*%
%ADD11R,0.2X0.2*%
%SRX2Y1I0.2J0*%
D10*
${at(0.2, 0.2)}D03*
%LPC*%
D11*
${at(0.2, 0.2)}D03*
%LPD*%
%SR*%`;
    // Copy 1: 0–0.4 with its centre 0.1–0.3 cleared. Copy 2 (0.2–0.6) covers 0.2 on again, then its own
    // clear centre (0.3–0.5) takes away what is there, of copy 1 as of copy 2.
    const r = raster(boardOf(gerber(body)), window(0.8, 0.4));
    expect(picture(r)).toEqual(['######..', '#.#..#..', '#.#..#..', '######..']);
  });
});

describe('units', () => {
  it('reads an inch file into millimetres, the same cells as the metric file', () => {
    const inch = `%FSLAX24Y24*%\n%MOIN*%\n%ADD10R,0.1X0.1*%\nD10*\nX500Y500D03*\nM02*\n`;
    const metric = gerber(`%ADD10R,2.54X2.54*%\nD10*\n${at(1.27, 1.27)}D03*`);
    const a = boardOf(inch);
    expect(a.layers[0].units).toBe('in');
    expect(a.layers[0].boundsMm.x1).toBeCloseTo(2.54, 9);
    const win = window(3, 3);
    expect(picture(raster(a, win, 50))).toEqual(picture(raster(boardOf(metric), win, 50)));
  });
});

describe('the grid', () => {
  it('puts row 0 at the top (largest Y), takes the union of every layer as the window by default, and keeps pitches apart', () => {
    const set = boardOf(gerber(`%ADD10R,0.2X0.1*%\nD10*\n${at(0.1, 1.05)}D03*\n${at(0.9, 0.05)}D03*`));
    const r = rasteriseBoard(set, { expose: ['other'], pitchUm: { x: 100, y: 50 }, threshold: 0.5 });
    expect(r.windowMm).toEqual({ x0: 0, y0: 0, x1: 1, y1: 1.1 });
    expect([r.cols, r.rows]).toEqual([10, 22]);
    expect(picture(r)[0]).toBe('##........');
    expect(picture(r)[21]).toBe('........##');
  });

  it('exposes nothing of layers not chosen, and has no cells for an empty window', () => {
    const set = boardOf(gerber(`%ADD10R,1X1*%\nD10*\n${at(0.5, 0.5)}D03*`), 'board-F_Cu.gbr');
    expect(count(rasteriseBoard(set, { expose: ['copper-bottom'], pitchUm: { x: 100, y: 100 }, threshold: 0.5 }))).toBe(0);
    expect(count(rasteriseBoard(set, { expose: ['board-F_Cu.gbr'], pitchUm: { x: 100, y: 100 }, threshold: 0.5 }))).toBe(100);
    expect(rasteriseBoard({ layers: [], problems: [], notes: [] }, { expose: [], pitchUm: { x: 50, y: 50 }, threshold: 0.5 }).cells.length).toBe(0);
    expect(() => rasteriseBoard(set, { expose: [], pitchUm: { x: 0, y: 50 }, threshold: 0.5 })).toThrow(RangeError);
  });

  it('exposes at a threshold of 0 only cells the artwork touches, and refuses one outside 0–1', () => {
    const set = boardOf(gerber(`%ADD10R,0.3X0.2*%\nD10*\n${at(0.25, 0.2)}D03*`));
    expect(picture(raster(set, window(0.6, 0.4), 100, { threshold: 0 }))).toEqual(['......', '.###..', '.###..', '......']);
    expect(() => raster(set, window(0.6, 0.4), 100, { threshold: 50 })).toThrow(RangeError);
  });

  it('exposes a cell from the threshold on: lower takes more of the edge cells, higher fewer', () => {
    const set = boardOf(gerber(`%ADD10C,1*%\nD10*\n${at(1, 1)}D03*`));
    const at30 = count(raster(set, window(2, 2), 50, { threshold: 0.3 }));
    const at50 = count(raster(set, window(2, 2), 50, { threshold: 0.5 }));
    const at90 = count(raster(set, window(2, 2), 50, { threshold: 0.9 }));
    expect(at30).toBeGreaterThan(at50);
    expect(at50).toBeGreaterThan(at90);
  });
});

describe('drill holes in copper', () => {
  const copper = gerber(`%ADD10C,1.6*%\n%ADD11R,0.4X0.4*%\nD10*\n${at(1, 1)}D03*\nD11*\n${at(3, 1)}D03*`);
  const drill = 'M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0Y1.0\nX3.0Y1.0\nX5.0Y1.0\nM30\n';
  const set = readBoard([
    { name: 'board-F_Cu.gbr', text: copper },
    { name: 'board-PTH.drl', text: drill },
  ]);
  const opts = (drillClear: RasteriseOptions['drillClear'], expose = ['copper-top']): RasteriseOptions => ({
    expose,
    pitchUm: { x: 50, y: 50 },
    threshold: 0.5,
    drillClear,
    drillDotMm: 0.3,
    windowMm: { x0: 0, y0: 0, x1: 6, y1: 2 },
  });
  const cell = (r: ReturnType<typeof rasteriseBoard>, x: number, y: number) => r.cells[Math.floor((2 - y) / 0.05) * r.cols + Math.floor(x / 0.05)];

  it('leaves a dot unexposed at each hole centre, in copper only, the size asked', () => {
    const plain = rasteriseBoard(set, opts('none'));
    const dotted = rasteriseBoard(set, opts('unexposed-dot'));
    expect(cell(plain, 1.01, 1.01)).toBe(1);
    expect(cell(dotted, 1.01, 1.01)).toBe(0);
    expect(cell(dotted, 1.3, 1.01)).toBe(1); // the pad beyond the dot
    // The dot takes π·0.15² of each pad: 28 cells of 50 µm, give or take the edge cells.
    const taken = count(plain) - count(dotted);
    expect(taken).toBeGreaterThanOrEqual(2 * 24);
    expect(taken).toBeLessThanOrEqual(2 * 32);
    expect(coveredArea(plain) - coveredArea(dotted)).toBeCloseTo(2 * Math.PI * 0.15 * 0.15, 3);
  });

  it('exposes a dot at each hole centre when asked, even where the copper has none', () => {
    const dotted = rasteriseBoard(set, opts('exposed-dot'));
    expect(cell(dotted, 5.01, 1.01)).toBe(1);
    // New copper only at the hole with no pad: the dots inside the round pad and the square one add nothing.
    expect(coveredArea(dotted) - coveredArea(rasteriseBoard(set, opts('none')))).toBeCloseTo(Math.PI * 0.15 * 0.15, 3);
  });

  it('puts no dots on a layer that is not copper', () => {
    const outline = rasteriseBoard(set, opts('exposed-dot', ['drill']));
    expect(count(outline)).toBe(count(rasteriseBoard(set, opts('none', ['drill']))));
  });
});

describe('drilled slots in copper (Excellon G85, as EasyEDA writes them)', () => {
  // A 4 × 1.6 mm pad at (1..5, 0.2..1.8), with a 0.8 mm slot drilled through it from (2, 1) to (4, 1),
  // in EasyEDA's 3.3 millimetre format with leading zeros and signs.
  const copper = gerber(`%ADD10R,4X1.6*%\nD10*\n${at(3, 1)}D03*`);
  const drill = 'M48\nMETRIC,LZ,000.000\nT02C0.800\n%\nG05\nG90\nT02\nX+002000Y+001000G85X+004000Y+001000\nM30\n';
  const set = readBoard([
    { name: 'Gerber_TopLayer.GTL', text: copper },
    { name: 'Gerber_Drill_PTH.DRL', text: drill },
  ]);
  const opts = (drillClear: RasteriseOptions['drillClear'], drillDotMm?: number): RasteriseOptions => ({
    expose: ['copper-top'],
    pitchUm: { x: 50, y: 50 },
    threshold: 0.5,
    drillClear,
    drillDotMm,
    windowMm: { x0: 0, y0: 0, x1: 6, y1: 2 },
  });

  it('reads the slot: its two ends and its tool, no hole', () => {
    const drillLayer = set.layers.find((l) => l.kind === 'drill')!;
    expect(drillLayer.holes).toEqual([]);
    expect(drillLayer.slots).toHaveLength(1);
    const [slot] = drillLayer.slots;
    expect([slot.x0, slot.y0, slot.x1, slot.y1, slot.diameterMm].map((v) => +v.toFixed(6))).toEqual([2, 1, 4, 1, 0.8]);
    expect(set.problems).toEqual([]);
  });

  it('reads a routed path as slots too: a straight run, and an arc as chords on it', () => {
    const routed = 'M48\nMETRIC\nT1C1.0\n%\nT1\nG00X1.0Y1.0\nM15\nG01X3.0Y1.0\nG03X4.0Y0.0I1.0J0.0\nM16\nG05\nM30\n';
    const [layer] = readBoard([{ name: 'route.drl', text: routed }]).layers;
    expect(layer.slots[0]).toEqual({ x0: 1, y0: 1, x1: 3, y1: 1, diameterMm: 1 });
    const arc = layer.slots.slice(1);
    expect(arc.length).toBeGreaterThan(4);
    for (const s of arc) expect(Math.hypot(s.x1 - 4, s.y1 - 1)).toBeCloseTo(1, 6);
    expect([arc.at(-1)!.x1, arc.at(-1)!.y1].map((v) => +v.toFixed(6))).toEqual([4, 0]);
  });

  it('clears the dot along the slot, from one end to the other', () => {
    const plain = rasteriseBoard(set, opts('none'));
    // A 0.3 mm dot drawn along the 2 mm slot: a 2 × 0.3 mm band and a round end at each end.
    const dotted = rasteriseBoard(set, opts('unexposed-dot', 0.3));
    expect(coveredArea(plain) - coveredArea(dotted)).toBeCloseTo(2 * 0.3 + Math.PI * 0.15 * 0.15, 3);
    // By default as wide as the slot's tool, up to 0.4 mm.
    const byTool = rasteriseBoard(set, opts('unexposed-dot'));
    expect(coveredArea(plain) - coveredArea(byTool)).toBeCloseTo(2 * 0.4 + Math.PI * 0.2 * 0.2, 3);
  });
});
