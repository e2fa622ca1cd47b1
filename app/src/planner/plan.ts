// The plans the C++ planner's module hands the app (planner-wasm.ts decodes them), as the app holds
// them, and what the app reads off them: no planning here (protocol/planner.md).

import type { JobHeader } from '../protocol/job-types';
/** An event: from `t` µs after the pass's start mark the LEDs are in state `m` (bit k = LED k), as the Nano runs it (nano.md "Scan programs"). */
export type ScanEvent = [t: number, m: number];

export interface PlannerJob {
  header: JobHeader;
  /** rows arrays of cols values 0-255. */
  cells: ArrayLike<number>[];
  /**
   * For a job still arriving (stream mode, protocol/mega.md M828): only rows below this have arrived,
   * the rest read as 0. The plan then holds only the stops that no later row can change
   * (protocol/planner.md "Planning while rows arrive"), a prefix of the full job's plan.
   */
  knownRows?: number;
}

export interface Plan {
  count: number;
  hx: Int32Array;
  hy: Int32Array;
  /** 4 per stop, LED 0-3, µs. */
  durations: Uint32Array;
  passes: number;
  estimateUs: number;
  /** Head travel in µm, X and Y. */
  travelUm: [number, number];
}

export interface ScanPass {
  /** Head row. */
  hy: number;
  /** Towards −X (the 2nd, 4th, … pass). */
  descending: boolean;
  /** Smallest and largest head column with a lit cell; the pass has last − first + 1 windows. */
  first: number;
  last: number;
  /** The pass's window, µs: the job's, or longer where the link caps the pass (planner.md "The printhead link"); its time to speed and overscan. */
  windowUs: number;
  accelUs: number;
  overscanUm: number;
  /** Bed X (µm) where the pass starts and ends at rest. */
  runUpUm: number;
  runOutUm: number;
  /** Per LED 0-3: [on, off] µs after the start mark, in time order, touching intervals merged. */
  leds: [number, number][][];
  /** Blank stretches flown: [first blank window, windows, µs]. */
  jumps: [number, number, number][];
  /** The pass as the Nano runs it: [t µs after the mark, the LEDs' state from then on], one per switching moment. */
  events: ScanEvent[];
  /** The pass as the Mega runs it (planner.md "The stroke"): the step engine's move to the stroke's start, µs. */
  moveUs: number;
  /** The stroke's X ends, in steps; its µs from rest to idle, and the start mark's µs in it. */
  startSteps: number;
  stopSteps: number;
  strokeUs: number;
  markUs: number;
  /** The pass's whole time in the estimate: the move, the pass's load, the stroke, the Q that confirms it. */
  wallUs: number;
  /** The pass's chain of programs as the Mega sends it (nano.md "Scan programs"): all its lines' bytes, and the first two programs', loaded before the pass starts. */
  chainBytes: number;
  chainAheadBytes: number;
}

export interface ScanPlan {
  /** The job's cell window in µs (a pass's own may be longer: ScanPass.windowUs). */
  windowUs: number;
  /** round(pitch × 10⁶ / window), for display; the exact speed is pitch / window µm/µs. */
  speedUmS: number;
  /** Time to reach the speed from rest, and the distance it takes (µm), at the job's window. */
  accelUs: number;
  overscanUm: number;
  passes: ScanPass[];
  estimateUs: number;
  /** Why the Mega cannot run the job's passes, when it cannot (planner.md "Limits"): the plan is then empty. */
  refused?: string;
}

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

/** A pass's time from its start at rest to its end at rest, as the step engine runs its stroke. */
export function passSpanUs(pass: ScanPass): number {
  return pass.strokeUs;
}

/** The passes of a mixed plan: each on the move or of stops one, a band of stops its `band`. */
export function mixedPassCount(plan: Pick<MixedPlan, 'passes'>): number {
  return plan.passes.reduce((n, p) => n + (!p.scan && p.band ? p.band : 1), 0);
}
