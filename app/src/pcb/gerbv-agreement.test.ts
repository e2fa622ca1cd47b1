// Our cells against gerbv's raster of the same real exports (Debian's gerbv examples), cell for cell at 50 µm.
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { agreement, EXAMPLES, gerbvCells, gerbvExample as example, hasGerbv } from './gerbv-reference';
import { rasteriseBoard } from './rasterise';
import { readBoard } from './read-board';

const PITCH_UM = 50;
const MISSING = 'gerbv and its examples are missing: `bash scripts/system-deps.sh` installs them (Debian package gerbv)';

// A handful from several CAD tools, with the constructs each brings.
const CASES: { file: string; from: string }[] = [
  { file: 'eaglecad1/top-cop.gbx', from: 'Eagle: macros, 100 × 80 mm' },
  { file: 'orcad/rs232_cm.top', from: 'OrCAD: obrounds, negative coordinates' },
  { file: 'protel-pnp/SE_SG_IF_V2.GTL', from: 'Protel: 45 000 draws' },
  { file: 'hellboard/hellboard.front.gbr', from: 'gEDA PCB: polygon pours, thermals' },
  { file: 'Mentor-BoardStation/artwork_1.grb', from: 'Mentor BoardStation: millimetres, regions' },
  { file: 'jj/l1-orig.grb', from: 'Visula: regions with clear polarity (LPC)' },
  { file: 'dan/top_sr.gbx', from: 'step and repeat (SR)' },
  { file: 'thermal/dsp.GP1', from: 'thermal macros' },
  { file: 'hellboard/hellboard.plated-drill.cnc', from: 'gEDA PCB: Excellon, inch' },
  { file: 'nollezappare/ThruHolePlated.ncd', from: 'Veribest: Excellon, metric' },
];

const results: string[] = [];

describe('agreement with gerbv on real exports', () => {
  const dir = mkdtempSync(join(tmpdir(), 'gerbv-examples-'));
  afterAll(() => {
    rmSync(dir, { recursive: true, force: true });
    console.log(`\nCells agreeing with gerbv at ${PITCH_UM} µm (outside a one-cell band at gerbv's edges; all cells):\n${results.join('\n')}`);
  });

  it('has gerbv and its examples to compare with', () => {
    expect(hasGerbv(), MISSING).toBe(true);
    expect(existsSync(EXAMPLES), MISSING).toBe(true);
  });

  it.each(CASES)('$file ($from)', ({ file }) => {
    const source = example(file, dir);
    expect(source, `${file}: ${MISSING}`).not.toBeNull();
    const set = readBoard([{ name: file.split('/').pop()!, text: source!.text }]);
    expect(set.layers).toHaveLength(1);
    const layer = set.layers[0];
    // A window on a 0.1 mm grid half a millimetre around the artwork: gerbv takes its corner as a short number.
    const p = PITCH_UM / 1000;
    const x0 = Math.floor(layer.boundsMm.x0 * 10) / 10 - 0.5;
    const y0 = Math.floor(layer.boundsMm.y0 * 10) / 10 - 0.5;
    const cols = Math.ceil((layer.boundsMm.x1 + 0.5 - x0) / p);
    const rows = Math.ceil((layer.boundsMm.y1 + 0.5 - y0) / p);
    const started = performance.now();
    const ours = rasteriseBoard(set, { expose: [layer.file], pitchUm: { x: PITCH_UM, y: PITCH_UM }, threshold: 0.5, windowMm: { x0, y0, x1: x0 + cols * p, y1: y0 + rows * p } });
    const ms = performance.now() - started;
    const theirs = gerbvCells(source!.path, { cols, rows, x0, y0, pitchMm: p });
    const a = agreement(ours.cells, theirs, cols, rows);
    const interior = a.interiorAgree / a.interior;
    const pct = (v: number) => `${(100 * v).toFixed(3)} %`;
    results.push(
      `  ${file.padEnd(38)} ${`${cols} × ${rows}`.padStart(11)} cells  ${pct(interior).padStart(9)}  ${pct(a.allAgree / a.all).padStart(9)}  rasterised in ${ms.toFixed(0)} ms${set.problems.length ? `  (${set.problems.length} problem${set.problems.length > 1 ? 's' : ''}: ${set.problems[0].message})` : ''}`,
    );
    expect(interior, `${file}: ${pct(interior)} of cells agree away from edges`).toBeGreaterThanOrEqual(0.99);
  }, 300_000); // gerbv draws a large board in tiles, each a run of its own, on a shared machine
});
