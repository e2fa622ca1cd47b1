import { describe, expect, it } from 'vitest';
import { NEUTRAL_TONE } from '../studio/image/adjust';
import { decodeProject, encodeProject, ProjectError, type Project } from './project-file';
import { isBlank } from './cells-codec';

const PNG = 'data:image/png;base64,iVBORw0KGgo=';
const BOARD = `data:application/vnd.uv-exposure.board+json;base64,${btoa('{"files":[]}')}`;
const SVG = `data:image/svg+xml;base64,${btoa('<svg xmlns="http://www.w3.org/2000/svg" width="3mm" height="2mm"/>')}`;

function project(): Project {
  const cells = new Uint8Array(300 * 200);
  cells[0] = 255;
  cells[200 * 300 - 1] = 7;
  cells.fill(128, 1000, 5000);
  return {
    name: 'board',
    machine: { bedMm: { x: 15, y: 10 }, pitchUm: { x: 50, y: 50 } },
    exposure: { fullMs: 4.5, strategy: 'shortest', mJcm2: 12.5 },
    polarity: 'positive',
    paint: { cols: 300, rows: 200, cells },
    objects: [
      { kind: 'image', id: 1, x: -5, y: 3, w: 40, h: 20, name: 'logo.png', src: PNG, halftone: 'atkinson', threshold: 40, tone: { ...NEUTRAL_TONE, gamma: 1.4 } },
      { kind: 'text', id: 2, x: 10, y: 10, w: 80, h: 20, turn: 3, mirror: true, text: 'PCB\nrev 2', font: 'DejaVu Sans', bold: true, dose: 200 },
      { kind: 'svg', id: 3, x: 100, y: 50, w: 60, h: 40, turn: 1, name: 'board.svg', src: SVG, halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE } },
      { kind: 'frame', id: 5, x: 0, y: 0, w: 300, h: 200, line: 0, dose: 255 },
      {
        kind: 'board', id: 6, x: 20, y: 20, w: 200, h: 100, mirror: true, name: 'demo', src: BOARD, halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE },
        layers: [{ file: 'a-F_Cu.gbr', kind: 'copper-top', expose: false }, { file: 'a-B_Cu.gbr', kind: 'copper-bottom', expose: true }], drillClear: 'exposed-dot', marks: [{ x: 2, y: 3.5 }], leftOut: true, copperGuessed: 'a-F_Cu.gbr',
      },
    ],
  };
}

async function reject(edit: (f: Record<string, any>) => void): Promise<string> {
  const f = JSON.parse(await encodeProject(project()));
  edit(f);
  const e = await decodeProject(JSON.stringify(f)).catch((x) => x);
  expect(e).toBeInstanceOf(ProjectError);
  return (e as Error).message;
}

describe('project files', () => {
  it('come back as they were saved: cells, objects as turned and mirrored, machine, exposure and polarity', async () => {
    const p = project();
    const back = await decodeProject(await encodeProject(p));
    expect(back.paint.cells).toEqual(p.paint.cells);
    expect(back.objects).toEqual(p.objects);
    expect({ ...back, paint: null, objects: null }).toEqual({ ...p, paint: null, objects: null });
  });

  it('keep the scan strategy (exposure on the move), and refuse a strategy not known by name', async () => {
    const p = { ...project(), exposure: { fullMs: 4, strategy: 'scan' as const } };
    expect((await decodeProject(await encodeProject(p))).exposure).toEqual({ fullMs: 4, strategy: 'scan' });
    expect(await reject((f) => (f.exposure.strategy = 'spiral'))).toMatch(/^exposure\.strategy must be one of raster, serpentine, shortest, random, scan/);
  });

  it('pack a whole empty-but-for-a-trace 4096² bed into a few KB', async () => {
    const cells = new Uint8Array(4096 * 4096);
    cells.fill(255, 4096 * 2048, 4096 * 2048 + 4096);
    const text = await encodeProject({ ...project(), paint: { cols: 4096, rows: 4096, cells }, objects: [] });
    expect(text.length).toBeLessThan(40_000);
    expect(Buffer.compare((await decodeProject(text)).paint.cells, cells)).toBe(0); // toEqual takes seconds over 16 M cells
  });

  it('tell a blank painting by every cell, whatever its length, where its bytes start or how it is sliced', async () => {
    const cells = new Uint8Array(4099);
    expect(await isBlank(cells)).toBe(true);
    expect(await isBlank(cells, 3)).toBe(true);
    for (const at of [0, 3, 2048, 4095, 4096, 4098]) {
      cells[at] = 1;
      expect(await isBlank(cells), `a cell at ${at}`).toBe(false);
      expect(await isBlank(cells, 3), `a cell at ${at}, three words a slice`).toBe(false);
      expect(await isBlank(cells.subarray(1)), `a cell at ${at}, read from byte 1`).toBe(at === 0);
      cells[at] = 0;
    }
  });

  it('keep an empty painting as no cells at all', async () => {
    const p = { ...project(), paint: { cols: 300, rows: 200, cells: new Uint8Array(60_000) } };
    const f = JSON.parse(await encodeProject(p));
    expect(f.paint.cells).toBeNull();
    expect((await decodeProject(JSON.stringify(f))).paint.cells).toEqual(p.paint.cells);
  });

  it('refuse what is not a project, or a newer one, saying so', async () => {
    await expect(decodeProject('{"grid":')).rejects.toThrow(/not a project file/);
    await expect(decodeProject('{"name":"x"}')).rejects.toThrow(/not a project file/);
    expect(await reject((f) => (f.version = 3))).toMatch(/version 3; this app opens versions 1 to 2/);
  });

  it('name the field that is wrong', async () => {
    expect(await reject((f) => (f.objects[0].halftone = 'sepia'))).toMatch(/^objects\[0\]\.halftone must be one of/);
    expect(await reject((f) => (f.objects[0].src = 'https://example.com/a.png'))).toMatch(/^objects\[0\]\.src must be a picture embedded/);
    expect(await reject((f) => (f.objects[1].dose = 300))).toMatch(/^objects\[1\]\.dose must be a whole number from 0 to 255/);
    expect(await reject((f) => (f.objects[3].kind = 'circle'))).toMatch(/^objects\[3\]\.kind must be image, svg, board, text or frame/);
    expect(await reject((f) => (f.objects[3].id = 1))).toMatch(/two objects with the same id/);
    expect(await reject((f) => (f.objects[1].turn = 4))).toMatch(/^objects\[1\]\.turn must be a whole number from 0 to 3/);
    expect(await reject((f) => (f.objects[2].src = PNG))).toMatch(/^objects\[2\]\.src must be an SVG drawing embedded/);
    expect(await reject((f) => (f.objects[0].threshold = 0))).toMatch(/^objects\[0\]\.threshold must be a number from 0.1 to 100/);
    expect(await reject((f) => (f.objects[4].src = SVG))).toMatch(/^objects\[4\]\.src must be a board's files embedded/);
    expect(await reject((f) => (f.objects[4].layers[1].kind = 'copper-inner'))).toMatch(/^objects\[4\]\.layers\[1\]\.kind must be one of copper-top/);
    expect(await reject((f) => (f.objects[4].leftOut = 'yes'))).toMatch(/^objects\[4\]\.leftOut must be true or false/);
    expect(await reject((f) => (f.objects[4].copperGuessed = 3))).toMatch(/^objects\[4\]\.copperGuessed must be/);
    expect(await reject((f) => (f.objects[4].drillClear = 'drill'))).toMatch(/^objects\[4\]\.drillClear must be one of none/);
    expect(await reject((f) => (f.objects[4].marks = [{ x: 1 }]))).toMatch(/^objects\[4\]\.marks\[0\]\.y must be a number/);
    expect(await reject((f) => (f.polarity = 'both'))).toMatch(/^polarity must be negative or positive/);
    expect(await reject((f) => (f.paint.cols = 5000))).toMatch(/^paint\.cols must be a whole number from 1 to 4096/);
    expect(await reject((f) => (f.exposure.strategy = 'spiral'))).toMatch(/^exposure\.strategy must be one of/);
    expect(await reject((f) => (f.machine.pitchUm = 'fine'))).toMatch(/^machine\.pitchUm must be an object/);
  });

  it('open version 1 files: dry film, nothing turned, the threshold level in 255ths as the same cut in percent', async () => {
    const f = JSON.parse(await encodeProject(project()));
    f.version = 1;
    delete f.polarity;
    delete f.exposure.mJcm2;
    f.objects = [{ ...f.objects[0], level: 128, threshold: undefined }, f.objects[3]];
    const p = await decodeProject(JSON.stringify(f));
    expect(p.polarity).toBe('negative');
    expect(p.exposure).toEqual({ fullMs: 4.5, strategy: 'shortest' });
    expect(p.objects[0]).toMatchObject({ kind: 'image', threshold: (128 * 100) / 255 });
    expect(p.objects[0]).not.toHaveProperty('turn');
    expect(p.objects[1]).toEqual(project().objects[3]);
  });

  it('find damaged or mis-sized cells', async () => {
    expect(await reject((f) => (f.paint.cells = f.paint.cells.slice(0, -8) + 'AAAAAAAA'))).toMatch(/^paint\.cells (is not deflated data|holds \d+ cells)/);
    expect(await reject((f) => (f.paint.cells = '***'))).toMatch(/^paint\.cells is not base64/);
    expect(await reject((f) => (f.paint.rows = 100))).toMatch(/^paint\.cells holds 60000 cells, not the 30000 its size says/);
  });
});
