// A board as one studio object: its files embedded and read back, drawn with the layers, drill dots and marks it chooses.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { boardArtwork, boardFiles, boardSrc, type BoardLook } from './board-artwork';

const DIR = join(import.meta.dirname, '../../../e2e/fixtures/pcb');
const FILES = readdirSync(DIR).filter((f) => f.startsWith('demo-')).sort().map((name) => ({ name, text: readFileSync(join(DIR, name), 'utf8') }));
// B_Cu, Edge_Cuts, F_Cu, F_Mask, PTH: the window is the outline's centre line, 0 … 30 × 0 … 20 mm: 600 × 400 cells of 50 µm.
const KINDS = ['copper-bottom', 'outline', 'copper-top', 'mask-top', 'drill'] as const;
const look = (expose: string[], more: Partial<BoardLook> = {}): BoardLook => ({ layers: KINDS.map((kind) => ({ kind, expose: expose.includes(kind) })), drillClear: 'none', marks: [], ...more });
/** The cell over board mm (x, y), Y up. */
const at = (v: { width: number; values: Uint8Array }, x: number, y: number) => v.values[Math.floor((20 - y) / 0.05) * v.width + Math.floor(x / 0.05)];

describe('a board embedded in a project', () => {
  it('comes back file for file, whatever the names hold', () => {
    const files = [...FILES, { name: 'carte µ-été.gbr', text: 'G04 ü*\nM02*' }];
    expect(boardFiles(boardSrc(files))).toEqual(files);
    expect(() => boardFiles('data:image/png;base64,AAAA')).toThrow(/not a board/);
  });

  it('refuses files that draw nothing, saying why', () => {
    expect(() => boardArtwork(boardSrc([{ name: 'notes.txt', text: 'hello' }]))).toThrow(/notes\.txt/);
  });
});

describe('a board drawn for the studio', () => {
  const board = boardArtwork(boardSrc(FILES));

  it('spans its outline’s centre line, where the board is cut: the size it is placed at', () => {
    expect(board.windowMm).toEqual({ x0: 0, y0: 0, x1: 30, y1: 20 });
    expect(board.files).toEqual(FILES.map((f) => f.name));
  });

  it('shows the bare share of each cell: copper is 0, bare board 255', () => {
    const top = board.cover(600, 400, look(['copper-top']));
    expect(at(top, 5, 5)).toBe(0); // the square pad
    expect(at(top, 1, 15)).toBe(255);
    expect(board.cover(600, 400, look(['copper-bottom'])).values).not.toEqual(top.values);
    expect(board.cover(600, 400, look([])).values.every((v) => v === 255)).toBe(true);
  });

  it('clears a drill dot from the copper, or leaves the pad whole', () => {
    expect(at(board.cover(600, 400, look(['copper-top'], { drillClear: 'unexposed-dot' })), 5, 5)).toBe(255);
    expect(at(board.cover(600, 400, look(['copper-top'], { drillClear: 'exposed-dot' })), 5, 5)).toBe(0);
  });

  it('follows the kind the user gives a file: no copper, no drill dot', () => {
    const l = look(['copper-top'], { drillClear: 'unexposed-dot' });
    const asOther = { ...l, layers: l.layers.map((x) => (x.kind === 'copper-top' ? { kind: 'other' as const, expose: true } : x)) };
    expect(at(board.cover(600, 400, asOther), 5, 5)).toBe(0);
  });

  it('draws a registration mark as a copper ring with a bare centre, mm from the lower left corner', () => {
    const v = board.cover(600, 400, look([], { marks: [{ x: 2, y: 2 }] }));
    expect(at(v, 2, 2)).toBe(255);
    expect(at(v, 2.7, 2)).toBe(0);
    expect(at(v, 3.5, 2)).toBe(255);
  });

  it('draws at any size in cells over the same window', () => {
    const half = board.cover(300, 200, look(['copper-top']));
    expect(half.values).toHaveLength(300 * 200);
    expect(half.values[Math.floor(15 / 0.1) * 300 + Math.floor(5 / 0.1)]).toBe(0);
  });
});
