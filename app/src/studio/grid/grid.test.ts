import { describe, expect, it } from 'vitest';
import { DoseGrid } from './grid';
import { History } from './history';
import { floodFill, line, rectangle, stamp } from './tools';

function picture(g: DoseGrid): string[] {
  return Array.from({ length: g.rows }, (_, y) => Array.from(g.cells.subarray(y * g.cols, (y + 1) * g.cols), (v) => (v ? '#' : '.')).join(''));
}

describe('dose grid', () => {
  it('is machine-sized: the bed over the pitch, at most 4096 a side', () => {
    const g = DoseGrid.forBed({ x: 200, y: 150 }, { x: 50, y: 50 });
    expect([g.cols, g.rows]).toEqual([4000, 3000]);
    expect(DoseGrid.forBed({ x: 300, y: 300 }, { x: 50, y: 50 }).cols).toBe(4096);
    expect(() => new DoseGrid(0, 5)).toThrow(RangeError);
  });

  it('finds the box of what will be exposed', () => {
    const g = new DoseGrid(10, 8);
    expect(g.bounds()).toBeNull();
    const h = new History(g);
    const e = h.begin('dot');
    e.set(3, 2, 255);
    e.set(7, 5, 10);
    expect(g.bounds()).toEqual({ x0: 3, y0: 2, x1: 7, y1: 5 });
  });

  it('finds the same box four cells a word as one by one, wherever the cells lie', () => {
    for (const cols of [16, 15]) // a whole number of words a row, and not
      for (const [x, y] of [[0, 0], [3, 1], [4, 6], [cols - 1, 7], [9, 3]]) {
        const g = new DoseGrid(cols, 8);
        g.cells[y * cols + x] = 1;
        g.cells[7 * cols + 5] = 2;
        expect(g.bounds()).toEqual({ x0: Math.min(x, 5), y0: y, x1: Math.max(x, 5), y1: 7 });
      }
  });

  it('finds the same box a band of rows per task, with the page let run between', async () => {
    const g = new DoseGrid(300, 200);
    expect(await g.boundsSoon(async () => {}, 3000)).toBeNull();
    g.cells[17 * 300 + 250] = 3;
    g.cells[150 * 300 + 4] = 9;
    let pauses = 0;
    expect(await g.boundsSoon(async () => pauses++, 3000)).toEqual(g.bounds());
    expect(g.bounds()).toEqual({ x0: 4, y0: 17, x1: 250, y1: 150 });
    expect(pauses).toBe(19); // 10 rows a band
  });
});

describe('raster tools', () => {
  it('draws round brushes, lines without gaps, and rectangles outlined or filled', () => {
    const g = new DoseGrid(12, 9);
    const h = new History(g);
    const e = h.begin('draw');
    stamp(g, e, 2, 2, 5, 255); // cells whose centres lie within the brush's diameter
    expect(picture(g).slice(0, 5)).toEqual(['.###........', '#####.......', '#####.......', '#####.......', '.###........']);
    line(g, e, 0, 8, 11, 5, 1, 200);
    for (let x = 0; x < 12; x++) expect(g.cells.subarray(5 * 12, 9 * 12).filter((_, i) => i % 12 === x).some((v) => v === 200)).toBe(true);
    const r = new DoseGrid(6, 5);
    const er = new History(r).begin('rect');
    rectangle(r, er, 0, 0, 5, 4, false, 1, 255);
    expect(picture(r)).toEqual(['######', '#....#', '#....#', '#....#', '######']);
    rectangle(r, er, 4, 3, 1, 1, true, 1, 255);
    expect(picture(r)).toEqual(['######', '######', '######', '######', '######']);
  });

  it('flood-fills exactly the connected area, even a whole 4096² grid', () => {
    const g = new DoseGrid(8, 6);
    const h = new History(g);
    const e = h.begin('fill');
    rectangle(g, e, 1, 1, 6, 4, false, 1, 255);
    expect(floodFill(g, e, 3, 2, 255)).toBe(8);
    expect(picture(g)).toEqual(['........', '.######.', '.######.', '.######.', '.######.', '........']);
    expect(floodFill(g, e, 0, 0, 255)).toBe(48 - 24);
    const big = new DoseGrid(4096, 4096);
    const hb = new History(big);
    const eb = hb.begin('fill');
    expect(floodFill(big, eb, 100, 100, 7)).toBe(4096 * 4096);
  });

  it('undoes and redoes whole edits, and an empty edit is not a step', () => {
    const g = new DoseGrid(300, 200);
    const h = new History(g);
    const before = g.cells.slice();
    const e = h.begin('stroke');
    line(g, e, 0, 0, 299, 199, 5, 255);
    h.commit(e);
    const after = g.cells.slice();
    h.commit(h.begin('nothing'));
    expect(h.undoLabel).toBe('stroke');
    expect(h.undo()).toBe(true);
    expect(g.cells).toEqual(before);
    expect(h.lastChanged).toEqual({ x0: 0, y0: 0, x1: 299, y1: 199 }); // the tiles the stroke crossed
    expect(h.redo()).toBe(true);
    expect(g.cells).toEqual(after);
    expect(h.redo()).toBe(false);
    // A new edit after an undo drops the redo.
    h.undo();
    const e2 = h.begin('dot');
    e2.set(1, 1, 9);
    h.commit(e2);
    expect(h.canRedo).toBe(false);
  });

  it('keeps blank tiles as no bytes, and undoes a fill over blank and painted tiles alike', () => {
    const g = new DoseGrid(300, 200); // edge tiles narrower and shorter than 64
    const h = new History(g);
    const dot = h.begin('dot');
    dot.set(290, 190, 9);
    h.commit(dot);
    const before = g.cells.slice();
    const fill = h.begin('fill');
    rectangle(g, fill, 0, 0, 299, 199, true, 1, 200);
    h.commit(fill);
    expect([...fill.tiles.values()].filter((t) => t.length > 0)).toHaveLength(1); // only the dot's tile holds bytes
    const filled = g.cells.slice();
    h.undo();
    expect(Buffer.compare(g.cells, before)).toBe(0);
    h.redo();
    expect(Buffer.compare(g.cells, filled)).toBe(0);
    h.undo();
    h.undo();
    expect(g.cells.every((d) => d === 0)).toBe(true);
  });

  it('finds a single dose in a tile four cells a word or one by one, wherever the rows start', () => {
    // 131 columns: each row starts at another byte of a word; the grid itself off a word in its buffer
    for (const offset of [0, 1, 2, 3]) {
      const buffer = new Uint8Array(offset + 131 * 70);
      const g = new DoseGrid(131, 70, buffer.subarray(offset));
      for (const [x, y] of [[0, 0], [63, 5], [64, 63], [130, 69], [67, 66], [129, 1]]) {
        g.cells.fill(0);
        g.cells[y * 131 + x] = 7;
        const h = new History(g);
        const e = h.begin('fill');
        rectangle(g, e, 0, 0, 130, 69, true, 1, 200);
        h.commit(e);
        expect([...e.tiles.values()].filter((t) => t.length > 0), `dose at ${x}, ${y}, offset ${offset}`).toHaveLength(1);
        h.undo();
        expect(g.cells.reduce((n, d) => n + d, 0)).toBe(7);
        expect(g.cells[y * 131 + x]).toBe(7);
      }
    }
  });

  it('says which cells an undo rewrote: the tiles its edit saved, not the grid', () => {
    const g = new DoseGrid(4096, 4096);
    const h = new History(g);
    const e = h.begin('dot');
    e.set(100, 130, 255);
    expect(e.box()).toEqual({ x0: 64, y0: 128, x1: 127, y1: 191 });
    h.commit(e);
    h.undo();
    expect(h.lastChanged).toEqual({ x0: 64, y0: 128, x1: 127, y1: 191 });
  });

  it('reverts an edit that is not to be a step', () => {
    const g = new DoseGrid(50, 50);
    const h = new History(g);
    const e = h.begin('stroke');
    line(g, e, 0, 0, 49, 49, 3, 255);
    h.revert(e);
    expect(g.cells.every((v) => v === 0)).toBe(true);
    h.commit(e);
    expect(h.canUndo).toBe(false);
  });

  it('keeps its memory bounded by dropping the oldest steps', () => {
    const g = new DoseGrid(256, 256);
    const h = new History(g, 256 * 256 * 3);
    for (let i = 0; i < 10; i++) {
      const e = h.begin(`fill ${i}`);
      floodFill(g, e, 0, 0, i + 1);
      h.commit(e);
    }
    let steps = 0;
    while (h.undo()) steps++;
    expect(steps).toBe(3);
    expect(g.cells[0]).toBe(7); // back to before the oldest step kept
  });

  it('undoes steps outside the cells in the same order as cell edits', () => {
    const g = new DoseGrid(8, 8);
    const h = new History(g);
    let objects = ['a'];
    const e = h.begin('paint');
    e.set(1, 1, 9);
    h.commit(e);
    let saved = objects;
    objects = ['a', 'b'];
    h.record({ label: 'add b', swap: () => ([objects, saved] = [saved, objects]) });
    expect(h.undoLabel).toBe('add b');
    h.undo();
    expect(objects).toEqual(['a']);
    expect(g.get(1, 1)).toBe(9);
    expect(h.lastChanged).toBeNull(); // no cells to redraw
    h.undo();
    expect(g.get(1, 1)).toBe(0);
    h.redo();
    h.redo();
    expect(objects).toEqual(['a', 'b']);
    expect(g.get(1, 1)).toBe(9);
  });
});
