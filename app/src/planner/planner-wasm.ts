// The app's planner: the Mega's C++ planners as WebAssembly (firmware/wasm/planner_module.cpp, built
// by scripts/build-planner-wasm.sh into wasm/planner.wasm): planJob, planScan, planMixed, orderEstimates
// and the time model's moves and stops, their plans decoded from the module's words into plan.ts's
// objects. There is no other planner: the firmware's vectors check this one (planner-wasm.test.ts).

import type { JobHeader, StrategyName } from '../protocol/job-types';
import { NANO_LINK_BAUDS } from '../protocol/nano';
import type { MixedPass, MixedPlan, Plan, PlannerJob, ScanEvent, ScanPass, ScanPlan } from './plan';
import { ENGINE_MAX_RATE, ENGINE_TICK_HZ, type MotionModel } from './time-model';

interface Exports {
  memory: WebAssembly.Memory;
  _initialize(): void;
  planner_header(): number;
  planner_machine(): number;
  planner_cells(cols: number, rows: number): number;
  planner_plan(strategy: number, known: number, neverFly: number): number;
  planner_estimates(): number;
  planner_move_time_us(d: number, v: number, a: number): number;
  planner_engine_move_us(dx: number, dy: number): number;
  planner_stop_cost_us(dx: number, dy: number, us0: number, us1: number, us2: number, us3: number): number;
  planner_axis_steps(axis: number, um: number): number;
}

let planner: Exports | null = null;
let loading: Promise<void> | null = null;

/**
 * Where the module's bytes are: an asset of the app's build beside the work worker's file. Asked for
 * only when wanted: as a constant it would be code at the module's top, which follows this file into
 * the page's chunks that import the planner's types and helpers.
 */
const plannerUrl = (): URL => new URL('./wasm/planner.wasm', import.meta.url);

/** Compiles and starts the module from its bytes, synchronously (a worker's or Node's way); later calls keep the first. */
export function loadPlannerWasm(bytes: BufferSource): void {
  if (planner) return;
  const instance = new WebAssembly.Instance(new WebAssembly.Module(bytes), {});
  planner = instance.exports as unknown as Exports;
  planner._initialize();
}

/**
 * Fetches and starts the module once (the work worker, before its first plan). Fetched as bytes and
 * compiled in the worker, so any server's content type will do (the hub's flash, a static host). A
 * failed fetch is said, and the next call tries again.
 */
export function plannerReady(): Promise<void> {
  if (planner) return Promise.resolve();
  loading ??= fetch(plannerUrl())
    .then((r) => {
      if (!r.ok) throw new Error(`HTTP ${r.status}`);
      return r.arrayBuffer();
    })
    .then(loadPlannerWasm)
    .catch((e: Error) => {
      loading = null;
      // A page left open across a redeploy asks for a module the server no longer has.
      throw new Error(`the planner's module (planner.wasm) could not be loaded: ${e.message}. Reload the page if the app was updated`);
    });
  return loading;
}

function module(): Exports {
  if (!planner) throw new Error('the planner module is not loaded: plannerReady() (or loadPlannerWasm(bytes)) first');
  return planner;
}

/** The orders as the module numbers them (uv::Strategy). */
const STRATEGY_INDEX: Record<StrategyName, number> = { raster: 0, serpentine: 1, shortest: 2, random: 3, scan: 4, mixed: 5 };

/** The job's header as planner_module.cpp reads its words. */
function headerWords(h: JobHeader): number[] {
  const byTarget = h.fullUs === undefined;
  return [
    h.cols, h.rows, h.pitchUm[0], h.pitchUm[1], h.originUm[0], h.originUm[1], h.map === 'threshold' ? 1 : 0, h.level,
    byTarget ? 1 : 0, h.fullUs ?? 0, h.targetUJcm2 ?? 0, ...(h.irradianceUWcm2 ?? [0, 0, 0, 0]), ...h.gainPermille,
    ...h.offsets.flat(), STRATEGY_INDEX[h.strategy], h.seed, h.thermal[0], h.thermal[1],
  ];
}

let machineWritten: MotionModel | null = null;

function writeMachine(wasm: Exports, m: MotionModel): void {
  // A timeline asks a stop's cost at every stop: the same machine is written once (machines are not changed in place).
  if (m === machineWritten) return;
  // A link speed the Nano does not have is no machine to plan for.
  if (!NANO_LINK_BAUDS.includes(m.linkBaud)) throw new RangeError(`the printhead link has no speed ${m.linkBaud} baud (nano.md "Link speed")`);
  machineWritten = m;
  const words = [...m.vmaxUmS, ...m.accelUmS2, m.settleUs, m.overheadUs, ...m.startUm, ...m.stepsMilli, m.linkBaud];
  new Int32Array(wasm.memory.buffer, wasm.planner_machine(), words.length).set(words);
}

/** Writes the job's header and cells into the module. */
function writeJob(wasm: Exports, job: PlannerJob, machine: MotionModel): void {
  writeMachine(wasm, machine);
  const h = job.header;
  const words = headerWords(h);
  new Int32Array(wasm.memory.buffer, wasm.planner_header(), words.length).set(words);
  const at = wasm.planner_cells(h.cols, h.rows);
  if (!at) throw new RangeError(`the planner module cannot hold a job of ${h.cols} × ${h.rows} cells`);
  const cells = new Uint8Array(wasm.memory.buffer, at, h.cols * h.rows);
  cells.fill(0);
  for (let r = 0; r < h.rows; r++) cells.set(job.cells[r], r * h.cols);
}

/** Reads a plan's words in order (planner_module.cpp says what each is). */
class PlanWords {
  readonly #u: Uint32Array;
  readonly #i: Int32Array;
  #at = 1;
  constructor(wasm: Exports, at: number) {
    const count = new Uint32Array(wasm.memory.buffer, at, 1)[0];
    if (!count) throw new RangeError('the planner module ran out of memory for the plan');
    this.#u = new Uint32Array(wasm.memory.buffer, at, count);
    this.#i = new Int32Array(wasm.memory.buffer, at, count);
  }
  u32(): number {
    return this.#u[this.#at++];
  }
  i32(): number {
    return this.#i[this.#at++];
  }
  u64(): number {
    const lo = this.#u[this.#at++];
    return lo + this.#u[this.#at++] * 0x1_0000_0000;
  }
  /** n stops of [hx, hy, µs × 4]. */
  stops(n: number): number[][] {
    const out: number[][] = [];
    for (let s = 0; s < n; s++) out.push([this.i32(), this.i32(), this.u32(), this.u32(), this.u32(), this.u32()]);
    return out;
  }
}

/** The job planned in `order`, whatever its header asks (planScan plans a scan of any header). */
function plan(job: PlannerJob, machine: MotionModel, order: StrategyName, neverFly = false): PlanWords {
  const wasm = module();
  writeJob(wasm, job, machine);
  const h = job.header;
  return new PlanWords(wasm, wasm.planner_plan(STRATEGY_INDEX[order], job.knownRows ?? h.rows, neverFly ? 1 : 0));
}

/** A stop-and-fire plan (raster, serpentine, shortest, random). */
export function planJob(job: PlannerJob, machine: MotionModel): Plan {
  const w = plan(job, machine, job.header.strategy);
  const count = w.u32(), passes = w.u32(), estimateUs = w.u64(), travelUm: [number, number] = [w.u64(), w.u64()];
  const hx = new Int32Array(count), hy = new Int32Array(count), durations = new Uint32Array(4 * count);
  for (let i = 0; i < count; i++) {
    hx[i] = w.i32();
    hy[i] = w.i32();
    for (let k = 0; k < 4; k++) durations[4 * i + k] = w.u32();
  }
  return { count, hx, hy, durations, passes, estimateUs, travelUm };
}

/** Each LED's [on, off] intervals from a pass's events: the state's bit k set from one to the next. */
function ledsOf(events: ScanEvent[]): [number, number][][] {
  const leds: [number, number][][] = [[], [], [], []];
  const on = [0, 0, 0, 0];
  let state = 0;
  for (const [t, m] of events) {
    for (let k = 0; k < 4; k++) {
      const was = (state >> k) & 1, now = (m >> k) & 1;
      if (!was && now) on[k] = t;
      else if (was && !now) leds[k].push([on[k], t]);
    }
    state = m;
  }
  return leds;
}

function scanPass(w: PlanWords): ScanPass {
  const hy = w.i32(), descending = w.u32() === 1, first = w.i32(), last = w.i32();
  const windowUs = w.u32(), accelUs = w.u32(), overscanUm = w.u32(), runUpUm = w.i32(), runOutUm = w.i32();
  const moveUs = w.u32(), startSteps = w.i32(), stopSteps = w.i32(), strokeUs = w.u32(), markUs = w.u32(), wallUs = w.u64();
  const chainBytes = w.u32(), chainAheadBytes = w.u32();
  const jumps: [number, number, number][] = [];
  for (let n = w.u32(); n > 0; n--) jumps.push([w.u32(), w.u32(), w.u32()]);
  const events: ScanEvent[] = [];
  for (let n = w.u32(); n > 0; n--) events.push([w.u32(), w.u32()]);
  const leds = ledsOf(events);
  return { hy, descending, first, last, windowUs, accelUs, overscanUm, runUpUm, runOutUm, leds, jumps, events, moveUs, startSteps, stopSteps, strokeUs, markUs, wallUs, chainBytes, chainAheadBytes };
}

/**
 * Why the step engine cannot run a window (mega.md M29, E29), worded for the dry run and the order list:
 * the module says only that it cannot, and at which window.
 */
function engineRefusal(machine: MotionModel, pitchUm: number, windowUs: number): string {
  const den = pitchUm * machine.stepsMilli[0];
  if (den === 0) return 'the X axis has no steps per mm';
  const q16 = (((2n * BigInt(windowUs) * 1_000_000n) << 16n) + BigInt(den) / 2n) / BigInt(den);
  const stepsS = den / windowUs;
  const speed = `${((pitchUm * 1000) / windowUs).toFixed(3)} mm/s (${stepsS < 100 ? stepsS.toFixed(1) : Math.round(stepsS)} steps/s)`;
  if (q16 < BigInt(ENGINE_TICK_HZ / ENGINE_MAX_RATE) << 16n) return `the scan speed ${speed} is over the step engine's ${ENGINE_MAX_RATE} steps/s`;
  return `the scan speed ${speed} makes a step longer than the step engine's 32.8 ms`;
}

/** How a scan or mixed plan ended: planned, empty, or refused (with why). */
function ending(w: PlanWords, machine: MotionModel, h: JobHeader): { empty: boolean; refused?: string } {
  const code = w.u32(), windowUs = w.u32();
  if (code === 2) return { empty: true, refused: engineRefusal(machine, h.pitchUm[0], windowUs) };
  return { empty: code === 1 };
}

/** A plan exposed on the move (protocol/planner.md "Scan mode"; `neverFly` for the bench's figure; the link cap always applies). */
export function planScan(job: PlannerJob, machine: MotionModel, opts: { neverFly?: boolean } = {}): ScanPlan {
  const w = plan(job, machine, 'scan', !!opts.neverFly);
  const motion = { windowUs: w.u32(), speedUmS: w.u32(), accelUs: w.u32(), overscanUm: w.u32() };
  const estimateUs = w.u64(), end = ending(w, machine, job.header), count = w.u32();
  if (end.empty) return { ...motion, passes: [], estimateUs: 0, ...(end.refused ? { refused: end.refused } : {}) };
  const passes: ScanPass[] = [];
  for (let p = 0; p < count; p++) passes.push(scanPass(w));
  return { ...motion, passes, estimateUs };
}

/** A plan in mixed mode (protocol/planner.md "Mixed mode"). */
export function planMixed(job: PlannerJob, machine: MotionModel): MixedPlan {
  const w = plan(job, machine, 'mixed');
  const windowUs = w.u32(), steps = w.u32(), estimateUs = w.u64(), end = ending(w, machine, job.header), count = w.u32();
  if (end.empty) return { windowUs, passes: [], steps: 0, estimateUs: 0, ...(end.refused ? { refused: end.refused } : {}) };
  const passes: MixedPass[] = [];
  for (let p = 0; p < count; p++) {
    const flags = w.u32(), band = w.u32();
    const base = { hy: w.i32(), descending: (flags & 2) !== 0, first: w.i32(), last: w.i32(), scanUs: w.u64(), stopsUs: w.u64() };
    if (flags & 1) passes.push({ ...base, scan: true, pass: scanPass(w) });
    else passes.push({ ...base, scan: false, stops: w.stops(w.u32()), ...(band ? { band } : {}) });
  }
  return { windowUs, passes, steps, estimateUs };
}

/** The orders the automatic choice weighs, in the order it prefers them on a tie. */
export const ORDERS: StrategyName[] = ['scan', 'mixed', 'serpentine', 'shortest', 'raster', 'random'];

/**
 * Each order's estimate for the job, µs: what the Mega's planner will count for it. An order that cannot
 * plan a job that has light is Infinity, and so is a scan or mixed plan whose strokes leave the bed.
 */
export function orderEstimates(job: PlannerJob, machine: MotionModel, bedXUm = Infinity): Record<StrategyName, number> {
  const wasm = module();
  writeJob(wasm, job, machine);
  const w = new PlanWords(wasm, wasm.planner_estimates());
  const byIndex = [0, 1, 2, 3, 4, 5].map(() => ({ estimateUs: w.u64(), steps: w.u32(), ending: w.u32(), strokes: w.u32(), lo: w.i32(), hi: w.i32() }));
  const bedSteps = Math.floor((bedXUm * machine.stepsMilli[0] + 500_000) / 1_000_000);
  const out = {} as Record<StrategyName, number>;
  let lit = false;
  for (const name of ORDERS) {
    const e = byIndex[STRATEGY_INDEX[name]];
    const planned = e.ending === 0;
    const offBed = planned && e.strokes === 1 && (e.lo < 0 || (Number.isFinite(bedXUm) && e.hi > bedSteps));
    const count = planned ? e.steps : 0, estimateUs = planned ? e.estimateUs : 0;
    out[name] = offBed ? Infinity : count || !lit ? estimateUs : Infinity;
    if (name !== 'scan' && name !== 'mixed' && count) lit = true;
  }
  if (lit && out.scan === 0) out.scan = Infinity;
  if (lit && out.mixed === 0) out.mixed = Infinity;
  return out;
}

/** µs to move `d` µm on one axis from rest to rest on the continuous trapezoid (time_model.cpp moveTimeUs). */
export function moveTimeUs(d: number, v: number, a: number): number {
  return module().planner_move_time_us(d, v, a) >>> 0;
}

/** µs the step engine takes to move by (dx, dy) steps from rest to rest (time_model.cpp engineMoveUs). */
export function engineMoveUs(m: MotionModel, dx: number, dy: number): number {
  const wasm = module();
  writeMachine(wasm, m);
  return wasm.planner_engine_move_us(Math.abs(dx), Math.abs(dy)) >>> 0;
}

/**
 * A stop's cost in the time model (protocol/planner.md "Time model", time_model.cpp stopCostStepsUs):
 * the step engine's move by (dx, dy) steps, the settle after a move, the overhead, its F line on the
 * printhead link and its longest exposure (`us`: its four on-times).
 */
export function stopCostUs(m: MotionModel, dx: number, dy: number, us: ArrayLike<number>): number {
  const wasm = module();
  writeMachine(wasm, m);
  return wasm.planner_stop_cost_us(dx, dy, us[0], us[1], us[2], us[3]) >>> 0;
}

/** An axis's position in steps for `um` µm, rounded half away from zero (the Mega's Motion::toSteps). */
export function axisSteps(m: MotionModel, axis: 0 | 1, um: number): number {
  const wasm = module();
  writeMachine(wasm, m);
  return wasm.planner_axis_steps(axis, um);
}
