// The preview's model of a scan job (exposure on the move): each pass as a line along X from its
// run-up to its run-out, and the light each cell gets, taken from the LEDs' switch times (the
// on-time inside each cell's window), so the picture is what the plan will switch, not what the
// cells ask for.

import type { ScanPass, ScanPlan } from '../planner/plan';
import type { MotionModel } from '../planner/time-model';
import type { PrintJob } from '../protocol/job-types';
import { emptyGrid, type PreviewGrid } from './exposure-preview';

/** Light per cell, pass by pass: entries `from[p]`…`from[p + 1] − 1` belong to pass p. */
export interface ScanDoses {
  from: Uint32Array;
  /** row × cols + col. */
  cell: Uint32Array;
  /** LED 0-3. */
  led: Uint8Array;
  us: Float64Array;
}

/** One pass for drawing: its row and its ends in cells (fractional, run-up first), and its direction. */
export interface ScanLine {
  row: number;
  fromCol: number;
  toCol: number;
  descending: boolean;
  /** A mixed job's pass of stops (planner.md "Mixed mode"): its stops' head columns, in order; absent for a pass on the move. */
  stops?: number[];
}

export interface ScanPreview {
  lines: ScanLine[];
  doses: ScanDoses;
  speedUmS: number;
  windowUs: number;
  /** Why the printer cannot run the job's passes (planner.md "Limits"), when it cannot. */
  refused?: string;
}

/** S(j) of planner.md "Scan mode": when each window starts after the mark, flown stretches included. */
export function windowStarts(pass: ScanPass, windowUs: number): Float64Array {
  const n = pass.last - pass.first + 1;
  const start = new Float64Array(n);
  const jumpAt = new Map(pass.jumps.map(([j, g, f]) => [j, [g, f]]));
  for (let j = 1; j < n; j++) {
    start[j] = start[j - 1] + windowUs;
    const jump = jumpAt.get(j);
    if (jump) {
      const [g, f] = jump;
      for (let b = j; b < j + g; b++) start[b] = start[j - 1] + windowUs; // blank: no light to place
      start[j + g] = start[j - 1] + windowUs + f;
      j += g;
    }
  }
  return start;
}

/** Each LED's on-time per cell, from its intervals cut at the windows' edges. */
export function scanDoses(job: PrintJob, scan: ScanPlan): ScanDoses {
  const { cols, rows } = job.grid;
  const cell: number[] = [], led: number[] = [], us: number[] = [];
  const from = new Uint32Array(scan.passes.length + 1);
  scan.passes.forEach((pass, p) => {
    const W = pass.windowUs;
    from[p] = cell.length;
    const start = windowStarts(pass, W);
    const n = start.length;
    pass.leds.forEach((intervals, k) => {
      const [dx, dy] = job.leds.offsets[k];
      const row = pass.hy + dy;
      if (row < 0 || row >= rows) return;
      let j = 0;
      for (const [on, off] of intervals) {
        while (j < n - 1 && start[j + 1] <= on) j++;
        for (let w = j; w < n && start[w] < off; w++) {
          const lit = Math.min(off, start[w] + W) - Math.max(on, start[w]);
          if (lit <= 0) continue;
          const col = (pass.descending ? pass.last - w : pass.first + w) + dx;
          if (col < 0 || col >= cols) continue;
          const c = row * cols + col;
          if (cell.length > from[p] && cell[cell.length - 1] === c && led[led.length - 1] === k) us[us.length - 1] += lit;
          else cell.push(c), led.push(k), us.push(lit);
        }
      }
    });
  });
  from[scan.passes.length] = cell.length;
  return { from, cell: Uint32Array.from(cell), led: Uint8Array.from(led), us: Float64Array.from(us) };
}

export function scanPreview(job: PrintJob, scan: ScanPlan): ScanPreview {
  const col = (um: number) => (um - job.originUm.x) / job.pitchUm.x;
  return {
    lines: scan.passes.map((p) => ({ row: p.hy, fromCol: col(p.runUpUm), toCol: col(p.runOutUm), descending: p.descending })),
    doses: scanDoses(job, scan),
    speedUmS: scan.speedUmS,
    windowUs: scan.windowUs,
    refused: scan.refused,
  };
}

/** The job's light up to (not including) pass `upTo`, binned as previewGrid bins a stop plan. */
export function scanPreviewGrid(job: PrintJob, doses: ScanDoses, upTo: number, maxSide = 512): PreviewGrid {
  const { cols } = job.grid;
  const grid = emptyGrid(job, maxSide);
  const { width, scale, doseUs, led } = grid;
  let maxUs = 0;
  const end = doses.from[Math.min(upTo, doses.from.length - 1)];
  for (let i = 0; i < doses.cell.length; i++) {
    const us = doses.us[i];
    maxUs = Math.max(maxUs, us);
    if (i >= end) continue;
    const c = doses.cell[i];
    const b = Math.floor(Math.floor(c / cols) / scale) * width + Math.floor((c % cols) / scale);
    if (us > doseUs[b]) (doseUs[b] = us), (led[b] = doses.led[i] + 1);
  }
  return { ...grid, maxUs };
}

/** The clock when each pass ends, µs, as planScan's estimate counts it. */
export function scanTimeline(_job: PrintJob, scan: ScanPlan, _machine: MotionModel): Float64Array {
  const out = new Float64Array(scan.passes.length);
  let t = 0;
  scan.passes.forEach((p, i) => {
    t += p.wallUs;
    out[i] = t;
  });
  return out;
}

/** Cells each LED exposes. */
export function scanCoverage(doses: ScanDoses): number[] {
  const n = [0, 0, 0, 0];
  for (let i = 0; i < doses.led.length; i++) n[doses.led[i]]++;
  return n;
}
