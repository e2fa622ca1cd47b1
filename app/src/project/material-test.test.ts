import { describe, expect, it } from 'vitest';
import { doseLabel, materialTestProject, stepDoses, type MaterialTestSpec } from './material-test';
import { decodeProject, encodeProject } from './project-file';

const machine = { bedMm: { x: 100, y: 80 }, pitchUm: { x: 50, y: 50 } };
const spec = (over: Partial<MaterialTestSpec> = {}): MaterialTestSpec => ({ kind: 'wedge', steps: 8, unit: 'ms', longest: 8, shortest: 1, patchMm: 8, machine, ...over });
/** A stand-in for the browser's fonts: each character 0.6 of the height. */
const measure = (t: { text: string }, h: number) => Math.ceil(0.6 * h * t.text.length);

describe('material test', () => {
  it('steps a wedge by √2, the longest last, each dose as the machine rounds it', () => {
    const d = stepDoses(spec());
    expect(d).toEqual([23, 32, 45, 64, 90, 128, 180, 255]);
    for (let i = 1; i < d.length; i++) expect(d[i] / d[i - 1]).toBeCloseTo(Math.SQRT2, 1);
  });

  it('steps a strip evenly from the shortest to the longest', () => {
    expect(stepDoses(spec({ kind: 'strip', steps: 5, shortest: 2, longest: 10 }))).toEqual([51, 102, 153, 204, 255]);
  });

  it('never asks for a dose of nothing, however many stops down', () => {
    expect(Math.min(...stepDoses(spec({ steps: 16 })))).toBe(1);
  });

  it('is a project: patches painted, labelled with their real times, the full dose the longest time', () => {
    const p = materialTestProject(spec(), measure);
    expect(p.exposure.fullMs).toBe(8);
    expect(p.paint.cols).toBe(2000);
    const doses = new Set(p.paint.cells);
    expect([...doses].sort((a, b) => a - b)).toEqual([0, 23, 32, 45, 64, 90, 128, 180, 255]);
    const labels = p.objects.filter((o) => o.kind === 'text').map((o) => (o.kind === 'text' ? o.text : ''));
    expect(labels[0]).toBe('√2 wedge from 8.00 ms');
    expect(labels.slice(1)).toEqual(['0.72 ms', '1.00 ms', '1.41 ms', '2.01 ms', '2.82 ms', '4.02 ms', '5.65 ms', '8.00 ms']);
    // Every label and patch is on the bed.
    for (const o of p.objects) {
      expect(o.x + o.w).toBeLessThanOrEqual(p.paint.cols);
      expect(o.y + o.h).toBeLessThanOrEqual(p.paint.rows);
    }
  });

  it('wraps onto more rows when the bed is narrow, and refuses what cannot fit', () => {
    const narrow = { ...machine, bedMm: { x: 40, y: 80 } };
    const p = materialTestProject(spec({ machine: narrow }), measure);
    const ys = new Set(p.objects.slice(1).map((o) => o.y));
    expect(ys.size).toBeGreaterThan(1);
    expect(() => materialTestProject(spec({ machine: { ...machine, bedMm: { x: 40, y: 20 } } }), measure)).toThrow(/does not fit/);
    expect(() => materialTestProject(spec({ kind: 'strip', shortest: 9 }), measure)).toThrow(/shortest time/);
    expect(() => materialTestProject(spec({ unit: 'mJ' }), measure)).toThrow(/needs the LEDs' calibrated irradiance/);
  });

  it('saves and opens as any project does', async () => {
    const p = materialTestProject(spec(), measure);
    const back = await decodeProject(await encodeProject(p));
    expect(back.objects).toEqual(p.objects);
    expect(Buffer.compare(back.paint.cells, p.paint.cells)).toBe(0);
  });

  it('in mJ/cm²: patches labelled with their energy, the project\'s full dose set in mJ/cm², its time LED 0\'s', () => {
    const p = materialTestProject(spec({ unit: 'mJ', longest: 40, irradianceUWcm2: [2e6, 2e6, 1.9e6, 2e6] }), measure);
    expect(p.exposure).toEqual({ fullMs: 20, strategy: 'serpentine', mJcm2: 40 });
    const labels = p.objects.map((o) => (o.kind === 'text' ? o.text : ''));
    expect(labels[0]).toBe('√2 wedge from 40.0 mJ/cm²');
    expect(labels.at(-1)).toBe('40.0 mJ/cm²');
    expect(labels[1]).toBe('3.61 mJ/cm²');
  });

  it('labels doses with three figures', () => {
    expect([doseLabel(0.7234, 'ms'), doseLabel(12.34, 'ms'), doseLabel(250, 'mJ')]).toEqual(['0.72 ms', '12.3 ms', '250 mJ/cm²']);
  });
});
