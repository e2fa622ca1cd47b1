// The material test: a row of square patches, each exposed with a different dose, labelled with
// it, as a project ready to run. The doses are times (ms a cell) or, where the LEDs' irradiance is
// calibrated, energy (mJ/cm², as resist datasheets give it; the project's full dose is then set in
// mJ/cm²). A test strip steps the dose evenly from the smallest to the largest; a √2 step wedge
// halves it every two steps down from the largest, as a photographer's stops do, so one exposure
// spans a wide range. Every patch's dose is what the machine will give: the cell's dose over 255
// of the job's full dose, so the labels show the rounding too.

import { DoseGrid } from '../studio/grid/grid';
import type { StudioObject, TextObject } from '../studio/objects/objects';
import type { Project } from './project-file';
import { msFor } from '../job/dose-units';

export interface MaterialTestSpec {
  kind: 'strip' | 'wedge';
  steps: number;
  /** The doses' unit: a time a cell, or energy (needs `irradianceUWcm2`). */
  unit: DoseUnit;
  longest: number;
  /** A strip's first step; a wedge ignores it. */
  shortest: number;
  /** The LEDs' calibrated irradiance, µW/cm², for doses in mJ/cm². */
  irradianceUWcm2?: number[];
  /** A patch's side. */
  patchMm: number;
  machine: Project['machine'];
}

export type DoseUnit = 'ms' | 'mJ';

export const DEFAULT_MATERIAL_TEST: Omit<MaterialTestSpec, 'machine'> = { kind: 'wedge', steps: 8, unit: 'ms', longest: 8, shortest: 1, patchMm: 8 };

/** Measures text: its width in cells at a height in cells (the browser's fonts, or a stand-in in tests). */
export type Measure = (t: Pick<TextObject, 'text' | 'font' | 'bold'>, h: number) => number;

const MARGIN_MM = 5;
const GAP_MM = 1.5;
const FONT = 'sans-serif';

/** Each patch's dose (1 … 255 of the largest), smallest first. */
export function stepDoses(s: Pick<MaterialTestSpec, 'kind' | 'steps' | 'longest' | 'shortest'>): number[] {
  const n = Math.max(2, Math.min(16, Math.round(s.steps)));
  const share = (i: number) => (s.kind === 'wedge' ? Math.SQRT1_2 ** (n - 1 - i) : (s.shortest + ((s.longest - s.shortest) * i) / (n - 1)) / s.longest);
  return Array.from({ length: n }, (_, i) => Math.max(1, Math.min(255, Math.round(255 * share(i)))));
}

/** A dose as a label: three figures, "0.72 ms" or "12.3 mJ/cm²". */
export function doseLabel(v: number, unit: DoseUnit): string {
  return `${v >= 100 ? v.toFixed(0) : v >= 10 ? v.toFixed(1) : v.toFixed(2)} ${unit === 'ms' ? 'ms' : 'mJ/cm²'}`;
}

export function checkSpec(s: MaterialTestSpec): string | null {
  const what = s.unit === 'ms' ? 'time' : 'dose';
  if (s.unit === 'mJ' && s.irradianceUWcm2?.length !== 4) return 'a dose in mJ/cm² needs the LEDs\' calibrated irradiance';
  if (!(s.longest > 0) || s.longest > (s.unit === 'ms' ? 60_000 : 100_000)) return `the longest ${what} must be more than 0 and at most ${s.unit === 'ms' ? '60 000 ms' : '100 000 mJ/cm²'}`;
  if (s.kind === 'strip' && !(s.shortest > 0 && s.shortest < s.longest)) return `the shortest ${what} must be more than 0 and less than the longest`;
  if (!(s.steps >= 2 && s.steps <= 16)) return 'a test has 2 to 16 steps';
  if (!(s.patchMm >= 1)) return 'a patch is at least 1 mm';
  return null;
}

export function materialTestProject(s: MaterialTestSpec, measure: Measure): Project {
  const problem = checkSpec(s);
  if (problem) throw new Error(problem);
  const { bedMm, pitchUm } = s.machine;
  const cx = (mm: number) => Math.round((mm * 1000) / pitchUm.x), cy = (mm: number) => Math.round((mm * 1000) / pitchUm.y);
  const { cols, rows } = DoseGrid.sizeForBed(bedMm, pitchUm);
  const doses = stepDoses(s);
  const labelMm = Math.max(1, Math.min(3, s.patchMm / 3));
  const perRow = Math.max(1, Math.floor((bedMm.x - 2 * MARGIN_MM + GAP_MM) / (s.patchMm + GAP_MM)));
  const rowMm = s.patchMm + labelMm + 2 * GAP_MM;
  const titleMm = labelMm;
  if (MARGIN_MM + titleMm + GAP_MM + Math.ceil(doses.length / perRow) * rowMm > bedMm.y) throw new Error('the test does not fit on the bed: use smaller patches or fewer steps');

  const cells = new Uint8Array(cols * rows);
  const objects: StudioObject[] = [];
  let id = 1;
  const text = (words: string, xMm: number, yMm: number, hMm: number): TextObject => {
    const t = { text: words, font: FONT, bold: false };
    const h = Math.max(1, cy(hMm));
    return { kind: 'text', id: id++, x: cx(xMm), y: cy(yMm), w: measure(t, h), h, ...t, dose: 255 };
  };
  const title = s.kind === 'wedge' ? `√2 wedge from ${doseLabel(s.longest, s.unit)}` : `Test strip ${doseLabel(s.shortest, s.unit)} to ${doseLabel(s.longest, s.unit)}`;
  objects.push(text(title, MARGIN_MM, MARGIN_MM, titleMm));
  doses.forEach((dose, i) => {
    const xMm = MARGIN_MM + (i % perRow) * (s.patchMm + GAP_MM);
    const yMm = MARGIN_MM + titleMm + GAP_MM + Math.floor(i / perRow) * rowMm;
    const x0 = cx(xMm), y0 = cy(yMm), w = Math.max(1, cx(s.patchMm)), h = Math.max(1, cy(s.patchMm));
    for (let y = y0; y < Math.min(rows, y0 + h); y++) cells.fill(dose, y * cols + x0, y * cols + Math.min(cols, x0 + w));
    objects.push(text(doseLabel((dose / 255) * s.longest, s.unit), xMm, yMm + s.patchMm + GAP_MM / 2, labelMm));
  });
  return {
    name: `Material test (${s.kind === 'wedge' ? '√2 wedge' : 'strip'}, ${doses.length} steps)`,
    machine: s.machine,
    exposure: s.unit === 'ms' ? { fullMs: s.longest, strategy: 'serpentine' } : { fullMs: msFor(s.longest, s.irradianceUWcm2![0]), strategy: 'serpentine', mJcm2: s.longest },
    polarity: 'negative', // the patches are exposures, not artwork
    paint: { cols, rows, cells },
    objects,
  };
}
