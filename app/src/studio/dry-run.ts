// The check before any LED fires (issue 8 "Job control"): the job is planned as the Mega will
// plan it, and the plan is held against the bed, the mesh, the printhead's exposure cap and
// the LEDs' thermal budget, and the machine's own faults; the drawing's objects are held against the bed's edges (a cut
// object is an error until the user accepts the cut), and a two-sided board's sides (one a job).
// Errors stop the job; warnings ask the user.

import { headerOf } from '../planner/job-header';
import type { Mesh } from '../planner/mesh';
import { planAnyJob, strokeOnBed, strokeSpanUm } from '../planner/job-plan';
import type { MixedPlan, Plan, ScanPass, ScanPlan } from '../planner/plan';
import { planJob } from '../planner/planner-wasm';
import type { PrintJob } from '../protocol/job-types';
import { machineFinding, type MachineCheck } from '../job/machine-finding';
import { hms } from '../job/hms';
import { mixedWords, scanWords } from '../job/scan-words';
import { bedOf, limitsOf, motionOf, type MachineConfig } from './machine-config';
import { cutWords, type Cut } from './objects/clipping';
import { sideInJob, type TwoSided } from './objects/board-object';
import { forecastMixedThermal, forecastScanThermal, forecastThermal, type ThermalRun } from './thermal-forecast';

export interface Finding {
  check: 'machine' | 'mode' | 'envelope' | 'clipping' | 'sides' | 'mesh' | 'dose' | 'thermal';
  level: 'error' | 'warning' | 'ok';
  message: string;
}

/** nano.md: the printhead refuses any single duration over this (NANO_MAX_EXPOSURE_US). */
export const NANO_MAX_EXPOSURE_US = 10_000_000;

export interface DryRun {
  /** For a scan job, one entry per pass. */
  plan: Plan;
  /** A scan job's plan (exposure on the move), else null. */
  scan: ScanPlan | null;
  /** A mixed job's plan, else null. */
  mixed: MixedPlan | null;
  findings: Finding[];
  /** Each LED's share of the job's time lit, 0-1. */
  duty: number[];
  /** The thermal forecast as the job would run, and, when that pauses, as it would run paced. */
  thermal: ThermalRun;
  paced: ThermalRun | null;
}

/** Objects cut by the bed's edge: an error, or once the user accepts the cut, a warning. */
export function clippingFinding(cuts: readonly Cut[], accepted: boolean): Finding {
  if (!cuts.length) return { check: 'clipping', level: 'ok', message: 'every object lies on the bed' };
  const what = cuts.map(cutWords).join('; ');
  return accepted
    ? { check: 'clipping', level: 'warning', message: `cut, accepted: ${what}. Only the part on the bed is exposed.` }
    : { check: 'clipping', level: 'error', message: `${what}. The part off the bed would not be exposed: move ${cuts.length > 1 ? 'them' : 'it'} onto the bed, or accept the cut.` };
}

/**
 * A two-sided board is exposed one side a job, the board turned over between them: both sides in one
 * job would expose them on top of each other (or the second side beside the first, on a board not yet
 * turned), so that is an error; the side the job exposes is said.
 */
export function sidesFinding(boards: readonly TwoSided[]): Finding | null {
  if (!boards.length) return null;
  const both = boards.filter((b) => b.sides.filter((s) => s.inJob).length > 1);
  if (both.length) return { check: 'sides', level: 'error', message: `${both.map((b) => `board ${b.name}`).join(', ')}: both sides are in the job, exposed on top of each other. A board is exposed one side at a time: leave one out` };
  return { check: 'sides', level: 'ok', message: `${boards.map((b) => sideInJob(b) ?? `no side of board ${b.name}`).join('; ')}. The other side is left out, for once the board is turned over` };
}

/**
 * `leveling` is whether the printer said exposures follow the mesh; null or absent if it did not
 * say. `cuts`: the drawing's objects cut by the bed's edge (absent for a job with no objects);
 * `boards`: its boards placed as two sides.
 * `startC` is the head's temperatures now (the printer's last report); a warm head pauses sooner.
 * `linkBaud`: the printhead link's speed the printer plans at (`Cap:LINK_BAUD`), BOARD_LINK_BAUD if absent.
 */
export function dryRun(
  job: PrintJob,
  config: MachineConfig,
  opts: { mesh?: Mesh | null; leveling?: boolean | null; linkBaud?: number; startC?: number[] | null; cuts?: readonly Cut[]; acceptCuts?: boolean; boards?: readonly TwoSided[]; machine?: MachineCheck; onStage?: (stage: string) => void } = {},
): DryRun {
  opts.onStage?.('planning');
  const header = headerOf(job);
  const machine = motionOf(config, [0, 0], opts.linkBaud);
  const { plan, scan, mixed } = planAnyJob({ header, cells: job.gridData }, machine);
  const findings: Finding[] = opts.machine ? [machineFinding(opts.machine)] : [];
  const { bedMm } = bedOf(config);
  if (scan) findings.push(scanFinding(scan));
  if (mixed) findings.push(mixedFinding(mixed));
  // A mixed job's passes on the move, by the index of their step in the plan.
  const strokes = new Map<number, ScanPass>();
  if (mixed) {
    let i = 0;
    for (const p of mixed.passes) {
      if (p.scan) strokes.set(i, p.pass);
      i += p.scan ? 1 : p.stops.length;
    }
  }

  // Envelope: every head position the plan stops at (for a scan job, each pass's stroke from its start
  // to its stop, as the Mega lays it out: a few steps beyond the run-up and run-out), on the bed.
  let minX = Infinity, minY = Infinity, maxX = -Infinity, maxY = -Infinity;
  let strokeOff = false;
  const bedUm = { x: bedMm.x * 1000, y: bedMm.y * 1000 };
  for (let i = 0; i < plan.count; i++) {
    const y = job.originUm.y + plan.hy[i] * job.pitchUm.y;
    const stroke = scan ? scan.passes[i] : strokes.get(i);
    if (stroke) {
      const span = strokeSpanUm(stroke, machine);
      minX = Math.min(minX, span.minUm), maxX = Math.max(maxX, span.maxUm);
      strokeOff ||= !strokeOnBed(stroke, machine, bedUm.x);
    } else {
      const x = job.originUm.x + plan.hx[i] * job.pitchUm.x;
      minX = Math.min(minX, x), maxX = Math.max(maxX, x);
      strokeOff ||= x < 0 || x > bedUm.x;
    }
    minY = Math.min(minY, y), maxY = Math.max(maxY, y);
  }
  const mm = (um: number) => (um / 1000).toFixed(1);
  if (plan.count && (strokeOff || minY < 0 || maxY > bedUm.y)) {
    findings.push({ check: 'envelope', level: 'error', message: `the head would go to X ${mm(minX)}–${mm(maxX)}, Y ${mm(minY)}–${mm(maxY)} mm, off the ${bedMm.x} × ${bedMm.y} mm bed` });
  } else {
    findings.push({ check: 'envelope', level: 'ok', message: plan.count ? `the head stays within X ${mm(minX)}–${mm(maxX)}, Y ${mm(minY)}–${mm(maxY)} mm` : 'nothing to expose' });
  }
  if (opts.cuts) findings.push(clippingFinding(opts.cuts, opts.acceptCuts ?? false));
  const sides = sidesFinding(opts.boards ?? []);
  if (sides) findings.push(sides);

  // Mesh: with leveling on, the job should lie within the probed points (beyond them Z is held at the edge).
  if (opts.leveling === false) findings.push({ check: 'mesh', level: 'ok', message: 'leveling is off: the whole job is exposed at one height' });
  else if (opts.leveling) {
    const m = opts.mesh;
    if (!m) findings.push({ check: 'mesh', level: 'warning', message: 'leveling is on but there is no mesh: probe the bed (G29) first' });
    else {
      const inside = minX >= m.x0 && minY >= m.y0 && maxX <= m.x0 + (m.nx - 1) * m.dx && maxY <= m.y0 + (m.ny - 1) * m.dy;
      findings.push(inside
        ? { check: 'mesh', level: 'ok', message: `the job lies within the ${m.nx} × ${m.ny} mesh` }
        : { check: 'mesh', level: 'warning', message: 'part of the job lies outside the probed mesh, where Z is held at the mesh edge' });
    }
  }

  // Dose: no single exposure over the printhead's cap.
  let longest = 0;
  const lit = [0, 0, 0, 0];
  for (let i = 0; i < plan.durations.length; i++) {
    longest = Math.max(longest, plan.durations[i]);
    lit[i & 3] += plan.durations[i];
  }
  // A scan job's cell is lit for its stop-mode on-time t_k(v) (an LED stays on across a run of full
  // cells, but each cell's exposure is its own): judged from the stop plan of the same passes, so a
  // scan the Mega cannot run (no passes) is judged too.
  if (scan || mixed) {
    const stops = planJob({ header: { ...header, strategy: 'serpentine' }, cells: job.gridData }, machine);
    for (let i = 0; i < stops.durations.length; i++) longest = Math.max(longest, stops.durations[i]);
  }
  for (const pass of scan?.passes ?? strokes.values()) pass.leds.forEach((list, k) => list.forEach(([on, off]) => (lit[k] += off - on)));
  findings.push(longest > NANO_MAX_EXPOSURE_US
    ? { check: 'dose', level: 'error', message: `${scan || mixed ? 'a cell' : 'a stop'} would light an LED for ${(longest / 1e6).toFixed(1)} s; the printhead refuses more than ${NANO_MAX_EXPOSURE_US / 1e6} s` }
    : { check: 'dose', level: 'ok', message: `the longest exposure is ${(longest / 1000).toFixed(1)} ms` });

  // Thermal: the plan played through the head's model, as the Mega reads and judges it.
  const duty = lit.map((us) => (plan.estimateUs ? us / plan.estimateUs : 0));
  const limitsC = limitsOf(config);
  const forecast = (paced: boolean) => {
    const o = { limitsC, startC: opts.startC ?? undefined, paced };
    return scan ? forecastScanThermal(scan, header, machine, o) : mixed ? forecastMixedThermal(mixed, header, machine, o) : forecastThermal(plan, header, machine, o);
  };
  opts.onStage?.('forecasting the heat');
  const thermal = forecast(false);
  if (thermal.pause) opts.onStage?.('forecasting the heat, paced');
  const paced = thermal.pause ? forecast(true) : null;
  findings.push(thermalFinding(thermal, paced, plan.count, limitsC, scan ? 'pass' : mixed ? 'step' : 'stop'));

  return { plan, scan, mixed, findings, duty, thermal, paced };
}

/** What a scan job is: its passes, their speed and the cell window. */
export function scanFinding(scan: ScanPlan): Finding {
  if (scan.refused) return { check: 'mode', level: 'error', message: `scan job (on the move): the printer cannot run it: ${scan.refused}. Choose a stop-and-fire order, or a dose that makes a shorter window` };
  if (!scan.passes.length) return { check: 'mode', level: 'ok', message: 'scan job (on the move): nothing to expose' };
  return { check: 'mode', level: 'ok', message: `scan job (on the move): ${scanWords(scan.passes.length, scan.speedUmS, scan.windowUs)}` };
}

/** What a mixed job is: which of its passes run on the move. */
export function mixedFinding(mixed: MixedPlan): Finding {
  if (mixed.refused) return { check: 'mode', level: 'error', message: `mixed job: the printer cannot run its passes on the move: ${mixed.refused}. Choose a stop-and-fire order, or a dose that makes a shorter window` };
  if (!mixed.passes.length) return { check: 'mode', level: 'ok', message: 'mixed job: nothing to expose' };
  return { check: 'mode', level: 'ok', message: `mixed job: ${mixedWords(mixed)}` };
}

function thermalFinding(run: ThermalRun, paced: ThermalRun | null, stops: number, limitsC: number[], unit: 'stop' | 'pass' | 'step'): Finding {
  const hottest = run.peakC.reduce((best, c, i) => (c - limitsC[i] > run.peakC[best] - limitsC[best] ? i : best), 0);
  const peak = (r: ThermalRun, i: number) => `T${i} ${r.peakC[i].toFixed(0)} °C (limit ${limitsC[i]} °C)`;
  if (!run.pause) return { check: 'thermal', level: 'ok', message: `the hottest sensor stays below its soft limit: ${peak(run, hottest)}` };
  const p = run.pause;
  const where = `T${p.sensor} would reach its ${limitsC[p.sensor]} °C soft limit ${hms(p.atUs)} in, at ${unit} ${p.stop + 1} of ${stops}: the job would pause there to cool`; // p.stop counts from 0, people from 1
  if (!paced || paced.pause) return { check: 'thermal', level: 'warning', message: `${where}, and pacing cannot prevent it (a single ${unit} heats too much): lower the dose` };
  const top = paced.peakC.reduce((best, c, i) => (c - limitsC[i] > paced.peakC[best] - limitsC[best] ? i : best), 0);
  return { check: 'thermal', level: 'warning', message: `${where}. Paced, it waits ${hms(paced.waitUs)} in all to cool, takes about ${hms(paced.totalUs)}, and stays below its limits (${peak(paced, top)})` };
}
