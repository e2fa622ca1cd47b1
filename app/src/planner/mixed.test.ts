// Mixed mode's properties (protocol/planner.md "Mixed mode") and the firmware's mixed vectors, checked on
// the app's planner: the C++ planner as WebAssembly.
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import type { PrintJob } from '../protocol/job-types';
import { headerOf } from './job-header';
import { planJob, planMixed, planScan } from './planner-wasm';
import { GEOMETRIES, MACHINE, mixedVector, planStops } from './test-jobs';
import type { MotionModel } from './time-model';

const plannerJob = (j: PrintJob) => ({ header: headerOf(j), cells: j.gridData });

/** A job on a blank grid, 50 µm cells, 2 ms a full cell, LEDs on adjacent rows. */
function job(cols: number, rows: number, lit: (x: number, y: number) => number, strategy: PrintJob['strategy']['name'] = 'mixed'): PrintJob {
  return {
    grid: { cols, rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 1000, y: 2000 },
    dose: { map: 'linear', fullUs: 2000 }, leds: { offsets: GEOMETRIES.adjacent }, strategy: { name: strategy },
    gridData: Array.from({ length: rows }, (_, y) => Array.from({ length: cols }, (_, x) => lit(x, y))),
  };
}
const as = (j: PrintJob, name: PrintJob['strategy']['name']): PrintJob => ({ ...j, strategy: { name } });

describe('the mixed planner', () => {
  it('takes a band of stops for a few dots far apart: `shortest`\'s stops column by column, with its estimate', () => {
    const dots = new Map([[0, 7], [5, 250], [9, 40], [17, 299], [22, 0]]);
    const j = job(300, 24, (x, y) => (dots.get(y) === x ? 255 : 0));
    const m = planMixed(plannerJob(j), MACHINE);
    const stops = planJob(plannerJob(as(j, 'shortest')), MACHINE);
    expect(m.passes).toHaveLength(1);
    const band = m.passes[0];
    expect(!band.scan && band.band).toBe(5);
    expect(band.stopsUs).toBeLessThan(band.scanUs); // against the five passes one by one
    expect(m.passes.flatMap((p) => (p.scan ? [] : p.stops))).toEqual(planStops(stops));
    expect(m.estimateUs).toBe(stops.estimateUs);
    expect(m.steps).toBe(stops.count);
  });

  it('takes each band the cheaper way: dense passes one by one on the move, a sparse band as stops', () => {
    const j = job(200, 64, (x, y) => (y < 32 ? (x >= 10 && x < 190 ? 255 : 0) : x === (y * 53) % 200 ? 255 : 0));
    const m = planMixed(plannerJob(j), MACHINE);
    expect(m.passes.map((p) => (p.scan ? 'scan' : `band ${p.band}`))).toEqual([...Array(8).fill('scan'), 'band 8']);
    for (const p of m.passes) expect(p.scan ? p.scanUs < p.stopsUs : p.stopsUs < p.scanUs).toBe(true);
    expect(m.estimateUs).toBe(m.passes.reduce((t, p) => t + (p.scan ? p.scanUs : p.stopsUs), 0));
    expect(m.steps).toBe(8 + 32);
  });

  it('takes the scan passes for full rows: the scan plan, with its estimate', () => {
    const j = job(60, 12, (x, y) => (x >= 3 && x < 57 ? 128 + ((x * 7 + y) % 128) : 0));
    const m = planMixed(plannerJob(j), MACHINE);
    const scan = planScan(plannerJob(as(j, 'scan')), MACHINE);
    expect(m.passes.map((p) => (p.scan ? p.pass : null))).toEqual(scan.passes);
    expect(m.estimateUs).toBe(scan.estimateUs);
    expect(m.steps).toBe(scan.passes.length);
  });

  it('prices each pass both ways and takes the cheaper, the stops on a tie', () => {
    const j = job(80, 32, (x, y) => ((y >> 2) % 2 === 0 ? 255 : y % 4 === 1 && x === (y * 37) % 80 ? 255 : 0));
    const m = planMixed(plannerJob(j), MACHINE);
    expect(m.passes).toHaveLength(8);
    for (const p of m.passes) expect(p.scan).toBe(p.scanUs < p.stopsUs);
    expect(m.estimateUs).toBe(m.passes.reduce((t, p) => t + Math.min(p.scanUs, p.stopsUs), 0));
    expect(m.passes.some((p) => p.scan) && m.passes.some((p) => !p.scan)).toBe(true);
    expect(m.estimateUs).toBeLessThan(planScan(plannerJob(as(j, 'scan')), MACHINE).estimateUs);
    expect(m.estimateUs).toBeLessThan(planJob(plannerJob(as(j, 'serpentine')), MACHINE).estimateUs);
  });

  it('plans a stream while its rows arrive: each plan a prefix of the whole job\'s, bands of stops among them', () => {
    const dense = (x: number, y: number) => ((y % 6 < 3 ? (x * 3 + y) % 4 !== 0 : (x * 11 + y * 7) % 31 === 0) ? 60 + ((x + y) % 190) : 0);
    const j = job(70, 60, (x, y) => (y < 24 ? dense(x, y) : y % 2 === 0 && x === (y % 4 ? 3 : 66) ? 255 : 0));
    const whole = mixedVector(planMixed(plannerJob(j), MACHINE)) as { passes: { band?: number }[] };
    expect(whole.passes.filter((p) => p.band).length).toBeGreaterThanOrEqual(1);
    let seen = 0;
    for (let known = 0; known <= 60; known++) {
      const part = mixedVector(planMixed({ ...plannerJob(j), knownRows: known }, MACHINE)) as { passes: object[] };
      expect(part.passes).toEqual(whole.passes.slice(0, part.passes.length));
      expect(part.passes.length).toBeGreaterThanOrEqual(seen);
      seen = part.passes.length;
    }
    expect(seen).toBe(whole.passes.length);
  });

  it('refuses what scan mode refuses: a window the step engine cannot run', () => {
    const j = job(20, 4, () => 255);
    j.dose = { map: 'linear', fullUs: 200_000 };
    const m = planMixed(plannerJob(j), MACHINE);
    expect(m.passes).toEqual([]);
    expect(m.refused).toMatch(/32.8 ms/);
  });
});

describe('mixed golden vectors', () => {
  const load = (file: string): { name: string; job: PrintJob; machine: MotionModel; mixed: object }[] => {
    const dir = process.env.UV_VECTORS_DIR ? `file://${process.env.UV_VECTORS_DIR}/` : new URL('../../../protocol/vectors/', import.meta.url);
    return JSON.parse(readFileSync(new URL(file, dir), 'utf8')).cases;
  };
  for (const file of ['mixed-cpp.json']) {
    it(`reproduces every mixed plan in ${file}, with passes of both ways`, () => {
      const cases = load(file);
      expect(cases.length).toBeGreaterThanOrEqual(10);
      for (const c of cases) expect(mixedVector(planMixed(plannerJob(c.job), c.machine)), c.name).toEqual(c.mixed);
      const ways = cases.flatMap((c) => (c.mixed as { passes: { scan: boolean; band?: number }[] }).passes);
      expect(ways.filter((p) => p.scan).length).toBeGreaterThan(5);
      expect(ways.filter((p) => !p.scan).length).toBeGreaterThan(5);
      expect(ways.filter((p) => p.band).length).toBeGreaterThan(2); // bands of stops too
      console.log(`[vectors] ${file}: ${cases.length} mixed plans checked (the C++ planner as WebAssembly)`);
    });
  }
});
