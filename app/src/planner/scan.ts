// The scan planner (protocol/planner.md "Scan mode"): passes exposed on the move, their LED switch times and a time estimate.

import type { JobHeader } from '../protocol/job-types';
import { durationTables } from './dose';
import { passRows, type PlannerJob } from './planner';
import { axisAccel, axisSteps, ENGINE_MAX_RATE, ENGINE_TICK_HZ, MoveTimes, stepRamp, stepTicks, type MotionModel } from './time-model';
import { mergeLight, programLines, PROGRAM_EVENTS, type ScanEvent } from '../protocol/scan-program';

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

const ceilDiv = (n: bigint, d: bigint) => (n + d - 1n) / d;
const roundDiv = (n: bigint, d: bigint) => (2n * n + d) / (2n * d);

/** The motion of a window W µs: its speed, the time to reach it from rest and the distance that takes (planner.md "Overscan"). */
export function passMotion(h: Pick<JobHeader, 'pitchUm'>, machine: MotionModel, windowUs: number): ScanMotion {
  const p = BigInt(h.pitchUm[0]), W = BigInt(windowUs);
  const tA = ceilDiv(p * 1_000_000_000_000n, BigInt(machine.accelUmS2[0]) * W);
  const o = ceilDiv(p * tA, 2n * W);
  return { windowUs, speedUmS: Number(roundDiv(p * 1_000_000n, W)), accelUs: Number(tA), overscanUm: Number(o) };
}

export interface ScanMotion {
  windowUs: number;
  speedUmS: number;
  accelUs: number;
  overscanUm: number;
}

/** The window, speed and overscan of a job's passes; windowUs 0 when nothing is lit. */
export function scanMotion(h: JobHeader, machine: MotionModel, tables = durationTables(h)): ScanMotion {
  const T = Math.max(...tables.map((t) => t[255]));
  if (T === 0) return { windowUs: 0, speedUmS: 0, accelUs: 0, overscanUm: 0 };
  const p = BigInt(h.pitchUm[0]);
  return passMotion(h, machine, Math.max(T, Number(ceilDiv(p * 1_000_000n, BigInt(machine.vmaxUmS[0])))));
}

/** Every switch time of every pass fits 32 bits: (cols + the LEDs' spread in X) × W < 2³² µs. */
export function fitsTimer(h: JobHeader, windowUs: number): boolean {
  const dx = h.offsets.map((o) => o[0]);
  return (h.cols + Math.max(...dx) - Math.min(...dx)) * windowUs < 2 ** 32;
}

/**
 * µs a byte takes on the link at `baud` as the AVR's UART runs it (U2X, UBRR (16 MHz/4/baud − 1)/2
 * rounded down: 85 at 115200, 40 at 250000; nano_codec.h linkByteUs).
 */
export const linkByteUs = (baud: number): number => 5 * (Math.floor((Math.floor(16_000_000 / 4 / baud) - 1) / 2) + 1);
/** The G step comes at least this long before a pass's start mark: the G's two bytes at the link's speed, then the Nano's 1000 µs lead (scan_stroke.h markLeadUs). */
export const strokeMarkLeadUs = (baud: number): number => 1000 + 2 * linkByteUs(baud);
/** After the stroke the Mega waits for the Nano's next Q answer (asked every 10 ms): half a poll on average. */
export const SCAN_PASS_END_US = 5000;
/** µs the Mega takes to start a pass once its move is done (planner.md "Scan mode"): not a stop's overhead (`overheadUs`). */
export const SCAN_PASS_LOAD_US = 400;

/**
 * A pass's step at window W as 16.16 timer ticks, or why the step engine cannot run it: over
 * ENGINE_MAX_RATE steps/s, or a step of 2¹⁶ ticks (32.768 ms) or more (mega.md M29, E29).
 */
export function engineStep(machine: MotionModel, pitchUm: number, windowUs: number): { q16: bigint } | { refused: string } {
  const den = BigInt(pitchUm) * BigInt(machine.stepsMilli[0]);
  if (den === 0n) return { refused: 'the X axis has no steps per mm' };
  const q16 = ((2n * BigInt(windowUs) * 1_000_000n << 16n) + den / 2n) / den;
  const stepsS = Number(den) / windowUs; // steps a window (den / 10⁶) over the window in s (W / 10⁶)
  const speed = `${((pitchUm * 1000) / windowUs).toFixed(3)} mm/s (${stepsS < 100 ? stepsS.toFixed(1) : Math.round(stepsS)} steps/s)`;
  if (q16 < BigInt(ENGINE_TICK_HZ / ENGINE_MAX_RATE) << 16n) return { refused: `the scan speed ${speed} is over the step engine's ${ENGINE_MAX_RATE} steps/s` };
  if (q16 >= 1n << 32n) return { refused: `the scan speed ${speed} makes a step longer than the step engine's 32.8 ms` };
  return { q16 };
}

const floorDivBig = (n: bigint, d: bigint) => (n >= 0n ? n / d : -((-n + d - 1n) / d));

/**
 * The stroke of a pass at the step `q16` whose start mark and last window's end are at twice the bed
 * X `markX2Um` and `endX2Um` (µm), as the Mega's scan_stroke.cpp lays it out (planner.md "The stroke").
 */
export function planStroke(machine: MotionModel, markX2Um: number, endX2Um: number, descending: boolean, q16: bigint, savedUs: number): Pick<ScanPass, 'startSteps' | 'stopSteps' | 'strokeUs' | 'markUs'> {
  const sign = descending ? -1n : 1n, S = BigInt(machine.stepsMilli[0]), den = 2_000_000n;
  const rate = Math.min(Number(((BigInt(ENGINE_TICK_HZ) << 16n) + q16 - 1n) / q16), ENGINE_MAX_RATE);
  const accel = axisAccel(machine, 0);
  const ramp = stepRamp([1, 0], [rate, 0], [accel, 1]).ramp;
  const mark = sign * BigInt(markX2Um) * S;
  const gAt = floorDivBig(mark, den) - ceilDiv((2n * BigInt(strokeMarkLeadUs(machine.linkBaud))) << 16n, q16) - 1n;
  const start = gAt - BigInt(ramp + 2);
  const stop = -floorDivBig(-(sign * BigInt(endX2Um) * S), den) + BigInt(ramp + 1);
  const n = Number(stop - start);
  const p = stepRamp([n, 0], [rate, 0], [accel, 1]);
  const up = stepTicks(p, 0, ramp);
  const ticks = BigInt(up) + ((BigInt(n - 2 * ramp) * q16) >> 16n) + BigInt(stepTicks(p, n - ramp, n));
  const markTicks16 = (BigInt(up) << 16n) + q16 + ((mark - gAt * den) * q16) / den;
  return {
    startSteps: Number(sign * start),
    stopSteps: Number(sign * stop),
    strokeUs: Number((ticks - 2n * BigInt(savedUs) + 1n) / 2n),
    markUs: Number((markTicks16 + 65536n) / 131072n),
  };
}

/** The printhead link's power-on speed (nano.md), what a board that never raises it runs at. */
export const LINK_BAUD = 115200;

/**
 * The relay: what the Mega takes from the Nano freeing a buffer to the next program's first byte (its
 * Q as the program before ends, the answer, a main-loop pass or two), and what a load loses besides
 * (planner.md "The printhead link"; the C++ kProgramRelayUs, measured in simavr).
 */
export const PROGRAM_RELAY_US = 10000;

/**
 * What the Mega's planner takes over an event as it writes a program's lines (the C++
 * kProgramEventUs, measured in simavr): a dense program goes out no faster than its events are made.
 */
export const PROGRAM_EVENT_US = 300;

/** µs `bytes` take on the printhead link at `baud`, ten bits a byte. */
const linkUs = (bytes: number, baud: number): bigint => (BigInt(bytes) * 10_000_000n) / BigInt(baud);
/** µs lines of `bytes` holding `events` take to go out at `baud`: the wire's time, or the planner's if longer. */
const sendUs = (bytes: number, events: number, baud: number): bigint => {
  const wire = linkUs(bytes, baud), made = BigInt(events * PROGRAM_EVENT_US);
  return wire > made ? wire : made;
};

/**
 * How far a pass's program lines outrun the printhead link (planner.md "The printhead link"), null
 * when they fit, else [need, have] of the first rule broken: the whole chain's (5 × its lines after
 * the first two programs' link µs against 4 × the pass's last event), else that of the first program
 * k ≥ 3 that would come too late (5 × its link µs + 4 × the relay against 4 × the µs program k − 1 plays).
 */
export function linkShortfall(events: ScanEvent[], baud: number): [bigint, bigint] | null {
  if (!events.length) return null;
  let bytes = 0, ahead = 0, aheadEvents = 0, sealed = 0, program = 0, end1 = 0, end2 = 0;
  let late: [bigint, bigint] | null = null;
  for (const line of programLines(events)) {
    bytes += line.length + 1;
    program += line.length + 1;
    if (!line.startsWith('K:')) continue;
    const held = Math.min((sealed + 1) * PROGRAM_EVENTS, events.length) - sealed * PROGRAM_EVENTS;
    if (++sealed === 2) {
      ahead = bytes;
      aheadEvents = Math.min(2 * PROGRAM_EVENTS, events.length);
    }
    if (sealed > 2 && !late) {
      const need = 5n * sendUs(program, held, baud) + 4n * BigInt(PROGRAM_RELAY_US), have = 4n * BigInt(end1 - end2);
      if (need > have) late = [need, have];
    }
    program = 0;
    end2 = end1;
    end1 = events[Math.min(sealed * PROGRAM_EVENTS, events.length) - 1][0];
  }
  const need = sealed > 2 ? 5n * sendUs(bytes - ahead, events.length - aheadEvents, baud) : 0n, have = 4n * BigInt(events[events.length - 1][0]);
  return need > have ? [need, have] : late;
}

/** The next window to try for a pass that outran the link at W: W stretched by need/have, and at least W + 1. */
export function linkWindow(W: number, [need, have]: [bigint, bigint]): number {
  const w = have > 0n ? Number(ceilDiv(BigInt(W) * need, have)) : 2 * W;
  return Math.max(W + 1, w);
}

/**
 * `neverFly`: a machine that cannot fly blank stretches crosses them at the pass's speed, so S(j) = j·W
 * throughout and the estimate is that of crossing (planner.md "Blank stretches"; bench P10's figure without flying).
 * `noLinkCap`: every pass at the job's window, however its programs load the link (bench P11's figure before the cap).
 */
export function planScan(job: PlannerJob, machine: MotionModel, opts: { neverFly?: boolean; noLinkCap?: boolean } = {}): ScanPlan {
  const h = job.header;
  const tables = durationTables(h);
  const motion = scanMotion(h, machine, tables);
  const plan: ScanPlan = { ...motion, passes: [], estimateUs: 0 };
  const W = motion.windowUs;
  if (W === 0 || !fitsTimer(h, W)) return plan;
  const jobStep = engineStep(machine, h.pitchUm[0], W);
  if ('refused' in jobStep) return { ...plan, refused: jobStep.refused };
  const Y = (hy: number) => h.originUm[1] + hy * h.pitchUm[1];
  const moves = new MoveTimes(machine);
  let curX = axisSteps(machine, 0, machine.startUm[0]), curY = machine.startUm[1];
  // Rows still to arrive (a stream): the plan is every pass up to the first that reads one of them
  // (planner.md "Planning while rows arrive"), a prefix of the whole job's.
  const known = job.knownRows ?? h.rows;
  const dyMax = Math.max(...h.offsets.map((o) => o[1]));

  for (const { hy, ledRows } of passRows(h, job.cells)) {
    if (known < h.rows && hy + dyMax >= known) break;
    const descending = plan.passes.length % 2 === 1;
    const full = planScanPass({ job, tables, motion, machine, moves, neverFly: !!opts.neverFly, noLinkCap: !!opts.noLinkCap }, ledRows, hy, descending, curX, curY);
    if (full === null) continue;
    if ('refused' in full) return { ...motion, passes: [], estimateUs: 0, ...(full.refused ? { refused: full.refused } : {}) };
    plan.estimateUs += passWallUs(full);
    curX = full.stopSteps;
    curY = Y(hy);
    plan.passes.push(full);
  }
  return plan;
}

/** What planning one scan pass needs: the job, its duration tables and motion, the machine. */
export interface ScanContext {
  job: PlannerJob;
  tables: Uint32Array[];
  motion: ScanMotion;
  machine: MotionModel;
  moves: MoveTimes;
  neverFly: boolean;
  noLinkCap: boolean;
}

/**
 * One scan pass from the head at (curX steps, curY µm): laid out, link-capped and stroked as the Mega
 * runs it; null when nothing is lit; `refused` when the plan must end there (the step engine cannot
 * run its window: why; or its link-capped window breaks the 32-bit limit: '').
 */
export function planScanPass(ctx: ScanContext, ledRows: number[], hy: number, descending: boolean, curX: number, curY: number): ScanPass | null | { refused: string } {
  const { job, tables, motion, machine, moves } = ctx;
  const h = job.header;
  let pass = layoutPass(job, tables, ledRows, hy, descending, motion, machine, moves, ctx.neverFly);
  if (!pass) return null;
  // The link cap: a pass whose program lines would outrun the link is laid out again at a longer window.
  for (let short = ctx.noLinkCap ? null : linkShortfall(pass.events, machine.linkBaud); short; short = linkShortfall(pass.events, machine.linkBaud)) {
    const w = linkWindow(pass.windowUs, short);
    if (!fitsTimer(h, w)) return { refused: '' };
    pass = layoutPass(job, tables, ledRows, hy, descending, passMotion(h, machine, w), machine, moves, ctx.neverFly)!;
  }
  // The pass as the Mega runs it (planner.md "The stroke"): the step engine's move to the stroke's
  // start, the overhead, the stroke, and the Nano's Q answer that confirms the pass.
  const step = engineStep(machine, h.pitchUm[0], pass.windowUs);
  if ('refused' in step) return { refused: step.refused };
  const X = (hx: number) => h.originUm[0] + hx * h.pitchUm[0];
  const p = h.pitchUm[0], dir = pass.descending ? -1 : 1;
  const x0 = X(pass.descending ? pass.last : pass.first), x1 = X(pass.descending ? pass.first : pass.last);
  const saved = (pass.last - pass.first + 1) * pass.windowUs - windowsSpanUs(pass);
  const stroke = planStroke(machine, 2 * x0 - dir * p, 2 * x1 + dir * p, pass.descending, step.q16, saved);
  const y = h.originUm[1] + hy * h.pitchUm[1];
  const moveUs = moves.engine(stroke.startSteps - curX, axisSteps(machine, 1, y) - axisSteps(machine, 1, curY));
  return { ...pass, moveUs, ...stroke };
}

/** S(n − 1) + W: a pass's windows with its flown stretches in their place. */
function windowsSpanUs(pass: Pick<ScanPass, 'first' | 'last' | 'windowUs' | 'jumps'>): number {
  let t = (pass.last - pass.first + 1) * pass.windowUs;
  for (const [, g, f] of pass.jumps) t += f - g * pass.windowUs;
  return t;
}

/** A pass's whole time in the estimate: the move to its stroke, the overhead, the stroke, the Q that confirms it. */
export function passWallUs(pass: ScanPass): number {
  return pass.moveUs + SCAN_PASS_LOAD_US + pass.strokeUs + SCAN_PASS_END_US;
}

/** A pass's time from its start at rest to its end at rest, as the step engine runs its stroke. */
export function passSpanUs(pass: ScanPass): number {
  return pass.strokeUs;
}

/** One pass laid out at the motion `m`: its extent, flown stretches, switch times and events; null when nothing is lit. */
export type LaidOutPass = Omit<ScanPass, 'moveUs' | 'startSteps' | 'stopSteps' | 'strokeUs' | 'markUs'>;

export function layoutPass(job: PlannerJob, tables: Uint32Array[], ledRows: number[], hy: number, descending: boolean, m: ScanMotion, machine: MotionModel, moves: MoveTimes, neverFly: boolean): LaidOutPass | null {
  const h = job.header;
  const p = h.pitchUm[0], W = m.windowUs;
  const X = (hx: number) => h.originUm[0] + hx * p;
  // A blank stretch of g windows may be flown in F(g) when that saves at least a window.
  const flies = !neverFly && W > Math.ceil((p * 1_000_000) / machine.vmaxUmS[0]);
  const fly = (g: number) => {
    if (!flies) return 0;
    const f = Math.max(1, moves.axis(0, g * p + 2 * m.overscanUm) - 2 * m.accelUs);
    return f <= (g - 1) * W ? f : 0;
  };
  let first = Infinity, last = -Infinity;
  ledRows.forEach((r, k) => {
    if (r < 0) return;
    const row = job.cells[r];
    for (let c = 0; c < row.length; c++) {
      if (tables[k][row[c]] === 0) continue;
      first = Math.min(first, c - h.offsets[k][0]);
      last = Math.max(last, c - h.offsets[k][0]);
    }
  });
  if (first > last) return null;
  const n = last - first + 1;
  const litAt = new Uint8Array(n); // by head column − first
  ledRows.forEach((r, k) => {
    if (r < 0) return;
    const row = job.cells[r];
    for (let c = 0; c < row.length; c++) if (tables[k][row[c]] > 0) litAt[c - h.offsets[k][0] - first] = 1;
  });
  // The flown stretches: by head column, the window after each lit one starts a stretch.
  const flown = new Map<number, number>(); // first blank window in the pass's direction → g
  for (const [col, g] of flownStretches(litAt, fly)) flown.set(descending ? n - col - g : col, g);
  const start = new Array<number>(n); // S(j)
  const jumps: [number, number, number][] = [];
  for (let j = 0, t = 0, prev = -1; j < n; j++, t += W) {
    if (litAt[descending ? n - 1 - j : j]) {
      const g = j - prev - 1;
      if (prev >= 0 && g > 0 && flown.get(prev + 1) === g) {
        const f = fly(g);
        t = start[prev] + W + f;
        jumps.push([prev + 1, g, f]);
      }
      prev = j;
    }
    start[j] = t;
  }
  const leds = ledRows.map((r, k) => (r < 0 ? [] : switchTimes(job.cells[r], tables[k], h.offsets[k][0], descending ? last : first, descending, W, start)));
  const reach = Math.ceil(p / 2) + m.overscanUm; // from a column's centre to the run-up
  const runUpUm = descending ? X(last) + reach : X(first) - reach;
  const runOutUm = descending ? X(first) - reach : X(last) + reach;
  return { hy, descending, first, last, windowUs: W, accelUs: m.accelUs, overscanUm: m.overscanUm, runUpUm, runOutUm, leds, jumps, events: mergeLight(leds) };
}

/** A pass flies at most this many of its blank stretches (planner.md "Blank stretches"). */
export const MAX_JUMPS = 8;

/**
 * The stretches a pass flies, as [lowest head column − first, g]: of the blank stretches between
 * lit windows that may be flown (fly(g) > 0), the MAX_JUMPS longest, the lower column first on a tie.
 */
function flownStretches(litAt: Uint8Array, fly: (g: number) => number): [number, number][] {
  const all: [number, number][] = [];
  for (let c = 0, prev = -1; c < litAt.length; c++) {
    if (!litAt[c]) continue;
    const g = c - prev - 1;
    if (prev >= 0 && g > 0 && fly(g) > 0) all.push([prev + 1, g]);
    prev = c;
  }
  return all.sort((a, b) => b[1] - a[1] || a[0] - b[0]).slice(0, MAX_JUMPS);
}

/** One LED's [on, off] list for its row: each lit cell centred in its window, touching intervals merged. */
function switchTimes(row: ArrayLike<number>, table: Uint32Array, dx: number, startHx: number, descending: boolean, W: number, start: number[]): [number, number][] {
  const out: [number, number][] = [];
  const n = row.length;
  for (let i = 0; i < n; i++) {
    const c = descending ? n - 1 - i : i;
    const t = table[row[c]];
    if (t === 0) continue;
    const j = descending ? startHx - (c - dx) : c - dx - startHx;
    const on = start[j] + Math.floor((W - t) / 2);
    const prev = out[out.length - 1];
    if (prev && prev[1] === on) prev[1] = on + t;
    else out.push([on, on + t]);
  }
  return out;
}
