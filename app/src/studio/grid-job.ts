// The editor's grid as an exposure job: cropped to what has a dose, placed where it lies on the bed.

import type { PrintJob } from '../protocol/job-types';
import type { Box, DoseGrid } from './grid/grid';
import type { BedGeometry } from './editor.svelte';

export interface ExposureSettings {
  dose: PrintJob['dose'];
  strategy: PrintJob['strategy'];
  leds: PrintJob['leds'];
}

export const DEFAULT_EXPOSURE: ExposureSettings = {
  dose: { map: 'linear', fullUs: 4000 },
  strategy: { name: 'serpentine' },
  leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
};

/** Null when nothing on the grid has a dose; `b`: the grid's bounds, when found already (DoseGrid.boundsSoon). */
export function jobFromGrid(grid: DoseGrid, machine: BedGeometry, settings: ExposureSettings, name = 'drawing', b: Box | null = grid.bounds()): PrintJob | null {
  if (!b) return null;
  const cols = b.x1 - b.x0 + 1, rows = b.y1 - b.y0 + 1;
  const gridData = Array.from({ length: rows }, (_, r) => grid.cells.subarray((b.y0 + r) * grid.cols + b.x0, (b.y0 + r) * grid.cols + b.x1 + 1));
  return {
    name,
    grid: { cols, rows },
    pitchUm: { ...machine.pitchUm },
    originUm: { x: b.x0 * machine.pitchUm.x, y: b.y0 * machine.pitchUm.y },
    dose: settings.dose,
    leds: settings.leds,
    strategy: settings.strategy,
    gridData,
  };
}
