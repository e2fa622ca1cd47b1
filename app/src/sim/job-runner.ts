// Runs a verified job on the simulated machine: plans it with the app's planner, then moves, settles and fires
// stop by stop (or exposes pass by pass on the move, for a scan job) in virtual time, checkpointing
// after each stop or pass so an interrupted job can resume.

import { planAnyJob } from '../planner/job-plan';
import type { Plan } from '../planner/planner';
import type { ScanPlan } from '../planner/scan';
import type { Machine } from '../planner/time-model';
import type { JobState } from '../protocol/dialect-reply';
import type { JobHeader } from '../protocol/job-types';
import { verifyJobText } from '../protocol/job-verify';
import { FAULT, formatNanoCommand, parseNanoReply } from '../protocol/nano';
import type { Clock } from './clock';
import { motionOf, num } from './config';
import type { Motion, Xyz } from './motion';
import type { NanoModel } from './nano-model';
import { paceWaits } from './pacing';
import { ScanPassRun, type ScanExposure } from './scan-pass';
import type { SdCard } from './sd-card';

export interface Exposure {
  stop: number;
  hx: number;
  hy: number;
  us: number[];
}

export class JobRunner {
  state: JobState = 'idle';
  file = '';
  plan: Plan | null = null;
  /** A scan job's plan; `plan` then counts its passes as stops. */
  scan: ScanPlan | null = null;
  header: JobHeader | null = null;
  done = 0;
  startedAtUs = 0;
  /** Every stop fired, in order: the tests' proof that each cell was exposed exactly once. */
  readonly exposures: Exposure[] = [];
  /** Every scan pass exposed whole, with each LED's on-intervals as the printhead switched them. */
  readonly scanExposures: ScanExposure[] = [];
  #pass: ScanPassRun | null = null;
  /** Why the job last paused or failed, for JOB: reports. */
  reason = '';
  /** Stream mode (M828): the plan is a prefix that grows as rows arrive, and there is no checkpoint. */
  streaming = false;
  #planComplete = true;
  #starved = false;
  /** Called after each exposed stop and whenever a streamed job runs out of planned stops. */
  onProgress: (() => void) | null = null;
  #pauseRequested = false;
  #step: object | null = null;
  /** Paced (protocol/mega.md "Pacing"): before a stop, wait while the head reads near a soft limit. */
  paced = false;
  /** A paced job waiting, LEDs off, for the head to cool before stop `#coolingStop`. */
  cooling = false;
  #coolingStop = -1;
  /** Time spent waiting to cool, µs. */
  cooledUs = 0;
  #coolingSince = 0;
  /** The Mega's latest temperature reading and its soft limits, 0.1 °C; the Mega sets these. */
  thermal: { reading(): number[]; limits(): number[] } = { reading: () => [], limits: () => [] };

  constructor(
    private readonly clock: Clock,
    private readonly motion: Motion,
    private readonly nano: NanoModel,
    private readonly sd: SdCard,
    private readonly config: Record<string, string>,
    private readonly report: (state: JobState) => void,
    private readonly fault: (code: number, message: string) => void,
  ) {}

  #elapsedUs = 0;
  #runningSince: number | null = null;

  /** Time spent running, µs, as the Mega counts it (job_runner.h elapsedS): not while paused, nor after the end. */
  elapsedUs(): number {
    return this.#elapsedUs + (this.#runningSince !== null ? this.clock.now - this.#runningSince : 0);
  }

  #report(state: JobState): void {
    if (state === 'running') this.#runningSince ??= this.clock.now;
    else if (this.#runningSince !== null) {
      this.#elapsedUs += this.clock.now - this.#runningSince;
      this.#runningSince = null;
    }
    this.report(state);
  }

  machine(start: Xyz): Machine {
    return motionOf(this.config, [start[0], start[1]]);
  }

  /** Loads and plans a job file; false if it is missing or does not verify. */
  load(file: string): boolean {
    const text = this.sd.files.get(file);
    if (text === undefined) return false;
    const { error, header } = verifyJobText(text);  // the header sizes the grid; a second pass fills it
    if (error || !header) return false;
    const cells = Array.from({ length: header.rows }, () => new Uint8Array(header.cols));
    verifyJobText(text, (s) => cells[s.row].set(s.cells, s.col));
    this.header = header;
    ({ plan: this.plan, scan: this.scan } = planAnyJob({ header, cells }, this.machine(this.motion.now())));
    this.file = file;
    this.done = 0;
    this.streaming = false;
    this.#planComplete = true;
    this.state = 'ready';
    return true;
  }

  /** Stream mode: runs as soon as stops are known, waiting whenever it reaches the last one planned so far. */
  beginStream(file: string): void {
    this.file = file;
    this.header = null;
    this.plan = null;
    this.scan = null;
    this.streaming = true;
    this.#planComplete = false;
    this.start(0);
  }

  /** A longer prefix of the streamed job's plan (protocol/planner.md "Planning while rows arrive"), and its passes for a scan job. */
  extend(header: JobHeader, plan: Plan, complete: boolean, scan: ScanPlan | null = null): void {
    this.header = header;
    this.plan = plan;
    this.scan = scan;
    this.#planComplete = complete;
    if (this.#starved && this.state === 'running' && (plan.count > this.done || complete)) {
      this.#starved = false;
      this.#next();
    }
  }

  /** False while a streamed job's plan is still a prefix: its end and its time left are not known yet. */
  get planComplete(): boolean {
    return this.#planComplete;
  }

  /** Waiting for rows in stream mode: every stop planned so far has been exposed. */
  get starved(): boolean {
    return this.#starved;
  }

  /** Starts from stop `from` (a resume starts after the checkpoint). */
  start(from = 0): void {
    this.done = from;
    this.cooledUs = 0;
    this.state = 'running';
    this.#pauseRequested = false;
    this.startedAtUs = this.clock.now;
    this.#elapsedUs = 0;
    this.#runningSince = null;
    this.reason = '';
    this.#report('running');
    this.#next();
  }

  pause(reason = 'user'): void {
    if (this.state !== 'running') return;
    if (this.cooling) {
      this.#endCooling();
      this.state = 'paused';
      this.reason = reason;
      this.#report('paused');
      return;
    }
    if (this.#starved) {
      this.#starved = false;
      this.state = 'paused';
      this.reason = reason;
      this.#report('paused');
      return;
    }
    this.#pauseRequested = true;
    this.reason = reason;
  }

  resume(): void {
    if (this.state !== 'paused') return;
    this.state = 'running';
    this.reason = '';
    this.#report('running');
    this.#next();
  }

  /** LEDs off, motion stopped, checkpoint cleared. */
  abort(): void {
    this.#cutPass();
    this.nano.allOff();
    this.nano.command('R\n');
    this.clock.cancel(this.#step);
    this.#starved = false;
    this.#endCooling();
    if (this.state === 'running' || this.state === 'paused' || this.state === 'ready') {
      this.state = 'aborted';
      this.sd.checkpoint = null;
      this.#report('aborted');
    }
  }

  /** Estimated time left in µs: the planner's model over the stops still to run. */
  remainingUs(): number {
    if (!this.plan) return 0;
    const p = this.plan;
    const total = p.estimateUs;
    return this.done >= p.count ? 0 : Math.round(total * (1 - this.done / p.count));
  }

  #next(): void {
    if (this.#pauseRequested) {
      this.#pauseRequested = false;
      this.state = 'paused';
      this.#report('paused');
      return;
    }
    const p = this.plan;
    const h = this.header;
    if (!p || !h || (this.done >= p.count && !this.#planComplete)) {
      this.#starved = true; // extend() carries on when the rows for the next stops have arrived
      this.onProgress?.();
      return;
    }
    if (this.done >= p.count) {
      this.state = 'done';
      this.sd.checkpoint = null;
      this.#report('done');
      return;
    }
    const i = this.done;
    if (this.scan) {
      const pass = this.scan.passes[i];
      return this.#goTo(i, [pass.runUpUm, h.originUm[1] + pass.hy * h.pitchUm[1], this.motion.pos[2]]);
    }
    this.#goTo(i, [h.originUm[0] + p.hx[i] * h.pitchUm[0], h.originUm[1] + p.hy[i] * h.pitchUm[1], this.motion.pos[2]]);
  }

  /**
   * To stop `i`, or a scan pass's run-up at its row, at the travel speed; then the settle (if the
   * head moved) and the overhead; then its exposure.
   */
  #goTo(i: number, to: Xyz): void {
    const from = this.motion.now();
    const moved = to[0] !== from[0] || to[1] !== from[1];
    this.motion.enqueue(to, num(this.config, 'speed.travel'));
    this.motion.whenIdle(() => {
      if (this.state !== 'running') return;
      const settle = moved ? num(this.config, 'settle_ms') * 1000 : 0;
      this.#step = this.clock.after(settle + num(this.config, 'stop_overhead_us'), () => this.#fireWhenCool(i));
    });
  }

  #runPass(i: number): void {
    const scan = this.scan!;
    const pass = scan.passes[i];
    const to: Xyz = [pass.runOutUm, this.motion.pos[1], this.motion.pos[2]];
    this.#pass = new ScanPassRun(this.clock, this.nano, scan, i, {
      moveUs: (us) => {
        this.motion.enqueueTimed(to, us);
        // The head stopped under a pass (M410): the LEDs must not go on lighting one place.
        const end = this.clock.now + us;
        this.motion.whenIdle(() => this.#pass && this.clock.now < end && this.faulted('stopped'));
      },
      refused: () => {
        const hot = this.#refusalWasHeat();
        this.#cutPass();
        this.fault(hot ? 31 : 33, hot ? `over-temperature in pass ${i}` : `printhead refused an exposure in pass ${i}`);
        this.faulted(hot ? 'overtemp' : 'refused');
      },
      done: (exposure) => {
        this.#pass = null;
        if (this.state !== 'running') return;
        this.scanExposures.push(exposure);
        this.done = i + 1;
        if (!this.streaming) this.#checkpoint(this.plan!.count);
        this.onProgress?.();
        if (this.state === 'running') this.#next();
      },
    });
  }

  /** Stops a pass under way at once: LEDs off, the head halted where it is. The pass is not counted. */
  #cutPass(): void {
    if (!this.#pass) return;
    this.#pass.cancel();
    this.#pass = null;
    this.nano.command('R\n'); // every LED off, and the chain and its armed programs dropped
    this.motion.stop();
  }

  #refusalWasHeat(): boolean {
    const flags = parseNanoReply(this.nano.command('E\n') ?? '');
    return flags?.op === 'E' && (flags.flags & FAULT.OVERTEMP) !== 0;
  }

  /** As the Mega's Settle phase: a paced job whose head reads near a soft limit waits for readings. */
  #fireWhenCool(i: number): void {
    if (this.state !== 'running') return;
    if (this.paced && paceWaits(this.thermal.reading(), this.thermal.limits(), false)) {
      this.cooling = true;
      this.#coolingStop = i;
      this.#coolingSince = this.clock.now;
      this.#report('running'); // the JOB: line says cooling=1
      return;
    }
    this.#fire(i);
  }

  /** A new temperature reading (every 500 ms, from the Mega's poll): a cooling job may go on. */
  reading(): void {
    if (!this.cooling || this.state !== 'running') return;
    if (paceWaits(this.thermal.reading(), this.thermal.limits(), true)) return;
    const i = this.#coolingStop;
    this.#endCooling();
    this.#report('running');
    this.#fire(i);
  }

  #endCooling(): void {
    if (!this.cooling) return;
    this.cooledUs += this.clock.now - this.#coolingSince;
    this.cooling = false;
    this.#coolingStop = -1;
  }

  #fire(i: number): void {
    if (this.scan) return this.#runPass(i);
    const p = this.plan!;
    const us = Array.from(p.durations.subarray(i * 4, i * 4 + 4));
    let mask = 0;
    us.forEach((d, k) => d && (mask |= 1 << k));
    this.nano.command(formatNanoCommand({ op: 'F', mask, durations: us as [number, number, number, number] }));
    if (mask && this.nano.lit === 0) {
      // The Mega polls S right after F: dark LEDs mean the printhead refused the exposure. Its E
      // flags say why; over-temperature is reported as the cause, not the refusal.
      const flags = parseNanoReply(this.nano.command('E\n') ?? '');
      const hot = flags?.op === 'E' && flags.flags & FAULT.OVERTEMP;
      if (hot) this.fault(31, `over-temperature at stop ${i}`);
      else this.fault(33, `printhead refused an exposure at stop ${i}`);
      this.faulted(hot ? 'overtemp' : 'refused');
      return;
    }
    const longest = Math.max(...us);
    this.#step = this.clock.after(longest, () => {
      if (this.state !== 'running') return;
      this.exposures.push({ stop: i, hx: p.hx[i], hy: p.hy[i], us });
      this.done = i + 1;
      if (!this.streaming) this.#checkpoint(p.count);
      this.onProgress?.();
      if (this.state === 'running') this.#next();
    });
  }

  #checkpoint(stops: number): void {
    const c = parseNanoReply(this.nano.command('C\n') ?? '');
    if (c?.op !== 'C') return; // the Mega keeps the checkpoint before: this stop is exposed again on resume
    this.sd.checkpoint = { file: this.file, done: this.done, stops, boot: c.boot, fires: c.fires };
  }

  /** A fault cut the LEDs mid-stop: the stop is not counted, and the job waits for the user. */
  faulted(reason: string): void {
    if (this.state !== 'running') return;
    this.#cutPass();
    this.clock.cancel(this.#step);
    this.#endCooling();
    this.nano.allOff();
    this.state = 'paused';
    this.reason = reason;
    this.#report('paused');
  }
}
