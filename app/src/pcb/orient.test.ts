import { describe, expect, it } from 'vitest';
import { rasteriseBoard, type BoardRaster } from './rasterise';
import { at, boardOf, coveredArea, gerber, picture } from './test-boards';

// An L of pads and a trace, with an obround and a rectangle at odd places, so any turn or flip shows.
const board = boardOf(
  gerber(`%ADD10R,0.3X0.2*%
%ADD11O,0.4X0.2*%
%ADD12C,0.1*%
%ADD13C,0.5X0.2*%
D10*
${at(0.25, 0.3)}D03*
D11*
${at(1.3, 0.4)}D03*
D13*
${at(0.6, 1.1)}D03*
D12*
${at(0.3, 0.3)}D02*
${at(1.2, 0.9)}D01*`),
);
const raster = (orient?: { mirror?: boolean; rotateDeg?: number }) => rasteriseBoard(board, { expose: ['other'], pitchUm: { x: 50, y: 50 }, threshold: 0.5, orient });

/** The cells turned a quarter counter-clockwise, or mirrored left to right. */
function turned(r: BoardRaster): string[] {
  const rows = picture(r);
  return Array.from({ length: r.cols }, (_, i) => rows.map((row) => row[r.cols - 1 - i]).join(''));
}
const mirrored = (r: BoardRaster) => picture(r).map((row) => [...row].reverse().join(''));

describe('orienting a board before rasterising', () => {
  it('turns by quarter turns exactly as turning the cells would', () => {
    const flat = raster();
    expect(picture(raster({ rotateDeg: 90 }))).toEqual(turned(flat));
    expect(picture(raster({ rotateDeg: 180 }))).toEqual(turned(raster({ rotateDeg: 90 })));
    expect(picture(raster({ rotateDeg: -90 }))).toEqual(picture(raster({ rotateDeg: 270 })));
  });

  it('mirrors as flipping the cells would, for a bottom layer seen from above', () => {
    expect(picture(raster({ mirror: true }))).toEqual(mirrored(raster()));
  });

  it('turns by any angle without losing area, round corners and all', () => {
    const area = coveredArea(raster());
    for (const rotateDeg of [10, 30, 45, 123]) expect(coveredArea(raster({ rotateDeg })) / area).toBeCloseTo(1, 2);
  });

  it('turns drill holes with the copper, so the dots stay on the pads', () => {
    const drill = 'M48\nMETRIC\nT1C0.8\n%\nT1\nX1.0Y2.0\nM30\n';
    const pad = gerber(`%ADD10C,1.6*%\nD10*\n${at(1, 2)}D03*`);
    const set = { layers: [...boardOf(pad, 'b-F_Cu.gbr').layers, ...boardOf(drill, 'b.drl').layers], problems: [], notes: [] };
    const r = rasteriseBoard(set, { expose: ['copper-top'], pitchUm: { x: 50, y: 50 }, threshold: 0.5, drillClear: 'unexposed-dot', drillDotMm: 0.3, orient: { rotateDeg: 37 } });
    // The pad's centre after the turn is where the window's middle is: unexposed there, exposed beside.
    const mid = Math.floor(r.rows / 2) * r.cols + Math.floor(r.cols / 2);
    expect(r.cells[mid]).toBe(0);
    expect(r.cells[mid + 8]).toBe(1);
  });

  it('turns drilled slots with the copper, so the dot runs along the slot', () => {
    // A 4 × 1.6 mm pad with a slot from (2, 1) to (4, 1); turned a quarter, the dot runs up the window's middle.
    const drill = 'M48\nMETRIC\nT1C0.8\n%\nT1\nX2.0Y1.0G85X4.0Y1.0\nM30\n';
    const pad = gerber(`%ADD10R,4X1.6*%\nD10*\n${at(3, 1)}D03*`);
    const set = { layers: [...boardOf(pad, 'b-F_Cu.gbr').layers, ...boardOf(drill, 'b.drl').layers], problems: [], notes: [] };
    const r = rasteriseBoard(set, { expose: ['copper-top'], pitchUm: { x: 50, y: 50 }, threshold: 0.5, drillClear: 'unexposed-dot', drillDotMm: 0.3, orient: { rotateDeg: 90 } });
    expect([r.cols, r.rows]).toEqual([32, 80]);
    const midCol = (row: number) => r.cells[row * r.cols + 16];
    // Down the middle column: copper at the pad's ends, the dot from 1 mm to 3 mm along it (rows 20 to 60, the dot's round ends beyond).
    expect([5, 15, 20, 40, 59, 65, 75].map(midCol)).toEqual([1, 1, 0, 0, 0, 1, 1]);
    expect(r.cells[40 * r.cols + 4]).toBe(1); // beside the dot
  });
});
