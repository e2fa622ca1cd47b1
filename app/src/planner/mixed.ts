// The mixed planner (protocol/planner.md "Mixed mode"): each band of passes as one group of stops, or
// pass by pass each a scan pass or a run of stops, whichever the time model prices cheaper.

import { durationTables } from './dose';
import { passRows, SHORTEST_BAND, type PassRows, type PlannerJob } from './planner';
import { engineStep, fitsTimer, passWallUs, planScanPass, scanMotion, type ScanPass } from './scan';
import { axisSteps, MoveTimes, type MotionModel } from './time-model';

interface MixedPassBase {
  hy: number;
  /** Towards −X (the 2nd, 4th, … pass), whichever way it is exposed. */
  descending: boolean;
  /** Smallest and largest head column with a lit cell. */
  first: number;
  last: number;
  /** The pass priced as a scan pass and as stops, µs (the estimate takes the way chosen). */
  scanUs: number;
  stopsUs: number;
}

/** A pass exposed on the move: `pass` as planScan lays it out. */
export interface MixedScanPass extends MixedPassBase {
  scan: true;
  pass: ScanPass;
}

/**
 * A pass exposed stop by stop: `[hx, hy, µs LED 0, 1, 2, 3]` in the pass's direction. Or a band of
 * stops (`band` passes, planner.md "Bands"): its passes' stops column by column; `hy` is its first
 * pass's, `descending` the columns' direction, `first` and `last` its extent, `scanUs` the band
 * priced pass by pass and `stopsUs` as this band of stops.
 */
export interface MixedStopPass extends MixedPassBase {
  scan: false;
  stops: number[][];
  band?: number;
}

export type MixedPass = MixedScanPass | MixedStopPass;

export interface MixedPlan {
  /** The job's scan window, µs (0 when nothing is lit). */
  windowUs: number;
  passes: MixedPass[];
  /** The Mega's progress count: one a scan pass, one a stop. */
  steps: number;
  estimateUs: number;
  /** Why the Mega cannot run the job's scan passes (planner.md "Limits"): the plan is then empty. */
  refused?: string;
}

/** A pass's stops: at each head column with a lit cell, each LED's on-time there, in the pass's direction. */
export function passStops(job: PlannerJob, tables: Uint32Array[], ledRows: number[], hy: number, descending: boolean): number[][] {
  const at = new Map<number, number[]>();
  ledRows.forEach((r, k) => {
    if (r < 0) return;
    const row = job.cells[r];
    for (let c = 0; c < row.length; c++) {
      const us = tables[k][row[c]];
      if (us === 0) continue;
      const hx = c - job.header.offsets[k][0];
      let stop = at.get(hx);
      if (!stop) at.set(hx, (stop = [hx, hy, 0, 0, 0, 0]));
      stop[2 + k] = us;
    }
  });
  return [...at.values()].sort((a, b) => (descending ? b[0] - a[0] : a[0] - b[0]));
}

/** Passes a band holds at most (planner.md "Bands"), as `shortest`'s. */
export const MIXED_BAND = SHORTEST_BAND;

/**
 * A band's stops column by column (planner.md "Bands"), as `shortest`'s order B: ascending head column
 * unless the far end of the band's extent is nearer the head's X (steps), each column's stops in head
 * row order from the end nearer the head's Y (µm; ties ascending). `passes`: each pass's stops, ascending.
 */
export function bandStops(passes: number[][][], xSteps: (hx: number) => number, Y: (hy: number) => number, curX: number, curY: number): { descending: boolean; first: number; last: number; stops: number[][] } {
  const first = Math.min(...passes.map((p) => p[0][0]));
  const last = Math.max(...passes.map((p) => p[p.length - 1][0]));
  const descending = Math.abs(xSteps(first) - curX) > Math.abs(xSteps(last) - curX);
  const idx = passes.map((p) => (descending ? p.length - 1 : 0));
  const stops: number[][] = [];
  let y = curY;
  for (;;) {
    let best = descending ? -Infinity : Infinity;
    passes.forEach((p, q) => {
      if (idx[q] < 0 || idx[q] >= p.length) return;
      best = descending ? Math.max(best, p[idx[q]][0]) : Math.min(best, p[idx[q]][0]);
    });
    if (!Number.isFinite(best)) break;
    const column: number[][] = [];
    passes.forEach((p, q) => {
      if (idx[q] < 0 || idx[q] >= p.length || p[idx[q]][0] !== best) return;
      column.push(p[idx[q]]);
      idx[q] += descending ? -1 : 1;
    });
    if (Math.abs(Y(column[0][1]) - y) > Math.abs(Y(column[column.length - 1][1]) - y)) column.reverse();
    stops.push(...column);
    y = Y(column[column.length - 1][1]);
  }
  return { descending, first, last, stops };
}

/** Plans a job in mixed mode; `knownRows` as planScan (a stream's prefix). */
export function planMixed(job: PlannerJob, machine: MotionModel): MixedPlan {
  const h = job.header;
  const tables = durationTables(h);
  const motion = scanMotion(h, machine, tables);
  const plan: MixedPlan = { windowUs: motion.windowUs, passes: [], steps: 0, estimateUs: 0 };
  const empty = (refused?: string): MixedPlan => ({ windowUs: motion.windowUs, passes: [], steps: 0, estimateUs: 0, ...(refused ? { refused } : {}) });
  if (motion.windowUs === 0 || !fitsTimer(h, motion.windowUs)) return plan;
  const jobStep = engineStep(machine, h.pitchUm[0], motion.windowUs);
  if ('refused' in jobStep) return empty(jobStep.refused);
  const moves = new MoveTimes(machine);
  const ctx = { job, tables, motion, machine, moves, neverFly: false, noLinkCap: false };
  const X = (hx: number) => h.originUm[0] + hx * h.pitchUm[0];
  const Y = (hy: number) => h.originUm[1] + hy * h.pitchUm[1];
  // The head in steps (X), and Y in µm as the scan planner keeps it.
  let curX = axisSteps(machine, 0, machine.startUm[0]), curY = machine.startUm[1];
  const known = job.knownRows ?? h.rows;
  const dyMax = Math.max(...h.offsets.map((o) => o[1]));
  const xSteps = (hx: number) => axisSteps(machine, 0, X(hx));
  /** Stops in their order from the head at (x steps, y µm): their time, and where the head ends (X in steps). */
  const priceStops = (stops: number[][], x: number, y: number): { us: number; x: number } => {
    let us = 0, ys = axisSteps(machine, 1, y);
    for (const [hx, hy, ...t] of stops) {
      const to = xSteps(hx), toY = axisSteps(machine, 1, Y(hy));
      us += moves.stopSteps(to - x, toY - ys, t);
      x = to;
      ys = toY;
    }
    return { us, x };
  };
  let band: PassRows[] = [];
  let opened = 0; // passes of the bands before
  const rows = passRows(h, job.cells);
  for (let i = 0; i <= rows.length; i++) {
    if (i < rows.length) {
      const { hy, ledRows } = rows[i];
      if (known < h.rows && hy + dyMax >= known) break;
      if (passStops(job, tables, ledRows, hy, false).length === 0) continue; // nothing lit: dropped
      band.push(rows[i]);
      if (band.length < MIXED_BAND) continue;
    } else if (band.length === 0 || known < h.rows) {
      break; // a row yet to come may still open a pass in this band
    }
    // The band pass by pass: each a scan pass or stops, whichever is cheaper from where the head stands.
    const byPasses: MixedPass[] = [];
    let x = curX, y = curY, passesUs = 0, steps = 0;
    for (const { hy, ledRows } of band) {
      const descending = (opened + byPasses.length) % 2 === 1; // the 2nd, 4th, … pass, whichever way it is exposed
      const pass = planScanPass(ctx, ledRows, hy, descending, x, y)!;
      if ('refused' in pass) return empty(pass.refused);
      const scanUs = passWallUs(pass);
      const stops = passStops(job, tables, ledRows, hy, descending);
      const asStops = priceStops(stops, x, y);
      const base = { hy, descending, first: pass.first, last: pass.last, scanUs, stopsUs: asStops.us };
      if (scanUs < asStops.us) {
        byPasses.push({ ...base, scan: true, pass });
        passesUs += scanUs;
        steps++;
        x = pass.stopSteps;
      } else {
        byPasses.push({ ...base, scan: false, stops });
        passesUs += asStops.us;
        steps += stops.length;
        x = asStops.x;
      }
      y = Y(hy);
    }
    // The band as one group of stops, column by column: taken when strictly cheaper.
    const cols = bandStops(band.map(({ hy, ledRows }) => passStops(job, tables, ledRows, hy, false)), xSteps, Y, curX, curY);
    const asBand = priceStops(cols.stops, curX, curY);
    if (asBand.us < passesUs) {
      plan.passes.push({ hy: band[0].hy, descending: cols.descending, first: cols.first, last: cols.last, scanUs: passesUs, stopsUs: asBand.us, scan: false, stops: cols.stops, band: band.length });
      plan.estimateUs += asBand.us;
      plan.steps += cols.stops.length;
      curX = asBand.x;
      curY = Y(cols.stops[cols.stops.length - 1][1]);
    } else {
      plan.passes.push(...byPasses);
      plan.estimateUs += passesUs;
      plan.steps += steps;
      curX = x;
      curY = y;
    }
    opened += band.length;
    band = [];
  }
  return plan;
}

/** The passes of a mixed plan: each on the move or of stops one, a band of stops its `band`. */
export function mixedPassCount(plan: Pick<MixedPlan, 'passes'>): number {
  return plan.passes.reduce((n, p) => n + (!p.scan && p.band ? p.band : 1), 0);
}

/** A mixed plan as the golden vectors write it (vectors/mixed-*.json). */
export function mixedVector(plan: MixedPlan): object {
  const passes = plan.passes.map((p) => {
    const base = { hy: p.hy, descending: p.descending, first: p.first, last: p.last, scanUs: p.scanUs, stopsUs: p.stopsUs, scan: p.scan };
    if (!p.scan) return { ...base, ...(p.band ? { band: p.band } : {}), stops: p.stops };
    const s = p.pass;
    return { ...base, windowUs: s.windowUs, jumps: s.jumps, events: s.events, moveUs: s.moveUs, startSteps: s.startSteps, stopSteps: s.stopSteps, strokeUs: s.strokeUs, markUs: s.markUs };
  });
  return { windowUs: plan.windowUs, passes, steps: plan.steps, estimateUs: plan.estimateUs };
}
