// The mixed planner (protocol/planner.md "Mixed mode"): each pass a scan pass or a run of stops, whichever the time model prices cheaper.

import { durationTables } from './dose';
import { passRows, type PlannerJob } from './planner';
import { engineStep, fitsTimer, passWallUs, planScanPass, scanMotion, type ScanPass } from './scan';
import { axisSteps, fireLineUs, MoveTimes, type Machine } from './time-model';

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

/** A pass exposed stop by stop: `[hx, hy, µs LED 0, 1, 2, 3]` in the pass's direction. */
export interface MixedStopPass extends MixedPassBase {
  scan: false;
  stops: number[][];
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

/** Plans a job in mixed mode; `knownRows` as planScan (a stream's prefix). */
export function planMixed(job: PlannerJob, machine: Machine): MixedPlan {
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
  for (const { hy, ledRows } of passRows(h, job.cells)) {
    if (known < h.rows && hy + dyMax >= known) break;
    const descending = plan.passes.length % 2 === 1;
    const pass = planScanPass(ctx, ledRows, hy, descending, curX, curY);
    if (pass === null) continue;
    if ('refused' in pass) return empty(pass.refused);
    const scanUs = passWallUs(pass);
    const stops = passStops(job, tables, ledRows, hy, descending);
    const ySteps = axisSteps(machine, 1, Y(hy));
    let x = curX, y = axisSteps(machine, 1, curY), stopsUs = 0;
    for (const [hx, , ...us] of stops) {
      const to = axisSteps(machine, 0, X(hx));
      const move = moves.engine(to - x, ySteps - y);
      stopsUs += move + (move > 0 ? machine.settleUs : 0) + machine.overheadUs + fireLineUs(us) + Math.max(...us);
      x = to;
      y = ySteps;
    }
    const base = { hy, descending, first: pass.first, last: pass.last, scanUs, stopsUs };
    if (scanUs < stopsUs) {
      plan.passes.push({ ...base, scan: true, pass });
      plan.estimateUs += scanUs;
      plan.steps++;
      curX = pass.stopSteps;
    } else {
      plan.passes.push({ ...base, scan: false, stops });
      plan.estimateUs += stopsUs;
      plan.steps += stops.length;
      curX = x;
    }
    curY = Y(hy);
  }
  return plan;
}

/** A mixed plan as the golden vectors write it (vectors/mixed-*.json). */
export function mixedVector(plan: MixedPlan): object {
  const passes = plan.passes.map((p) => {
    const base = { hy: p.hy, descending: p.descending, first: p.first, last: p.last, scanUs: p.scanUs, stopsUs: p.stopsUs, scan: p.scan };
    if (!p.scan) return { ...base, stops: p.stops };
    const s = p.pass;
    return { ...base, windowUs: s.windowUs, jumps: s.jumps, events: s.events, moveUs: s.moveUs, startSteps: s.startSteps, stopSteps: s.stopSteps, strokeUs: s.strokeUs, markUs: s.markUs };
  });
  return { windowUs: plan.windowUs, passes, steps: plan.steps, estimateUs: plan.estimateUs };
}
