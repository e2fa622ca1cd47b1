// The job the studio's drawing becomes, and what happens before and while it runs: the exposure
// settings (the full dose as a time, or in mJ/cm² through the LEDs' calibration), the dry run that
// must pass before any LED fires (loaded with the planner when first needed), framing with the
// LEDs off, and the run. What only one click needs (the test pattern, framing's moves) loads with it.

import type { Printer } from '../device/connection.svelte';
import type { PrintJob, StrategyName } from '../protocol/job-types';
import type { OrderChoice } from '../planner/job-plan';
import { num } from '../machine/config';
import type { Finding } from '../studio/dry-run';
import type { Cut } from '../studio/objects/clipping';
import type { TwoSided } from '../studio/objects/board-object';
import type { GridEditor } from '../studio/editor.svelte';
import { jobFromGrid } from '../studio/grid-job';
import type { DoseGrid } from '../studio/grid/grid';
import { DEFAULT_CONFIG, ledsOf, type MachineConfig } from '../studio/machine-config';
import { JobNotice } from './job-notice.svelte';
import { calibrationOf, doseOf, msFor, type Calibration } from './dose-units';
import { actionsFor, viewOf, type Action, type Actions } from './actions';
import { machineFinding, machineNow } from './machine-finding';
import { estimateUsFor, type JobEstimate } from './job-times';
import { limitsOf } from '../studio/machine-config';
import { uploadBytes, uploadUs, type LinkRate } from './link-rate';
import type { UploadSize } from './upload-time';

/** Lets the page draw and answer between two steps that each take a while. */
const nextTask = () => new Promise((r) => setTimeout(r));

/** What waits for the user's yes before anything moves or lights: an exposure, or a homing. */
export type Pending =
  | {
      kind: 'expose';
      what: 'drawing' | 'test pattern';
      job: PrintJob;
      findings: Finding[];
      duty: number[];
      estimateUs: number;
      /** When the job would pause to cool: its time run paced (mega.md "Pacing"), which the user may choose. */
      pacedUs: number | null;
      /** The upload before the exposure: its bytes, the link's rate and its time, µs. */
      upload: UploadSize;
      rate: LinkRate;
      uploadUs: number;
      /** Where the job's cells lie on the bed, mm. */
      areaMm: { x0: number; y0: number; x1: number; y1: number };
      /** The drawing's objects cut by the bed's edge, and whether the user accepted the cut. */
      cuts: Cut[];
      accepted: boolean;
      /** The drawing's boards placed as two sides: the job exposes one side of each. */
      boards: TwoSided[];
    }
  | { kind: 'home-first'; what: string; homed: boolean | null; run: () => Promise<unknown> };

export class JobControl {
  /** The exposure of a cell at 100 % dose, ms; for a dose set in mJ/cm², its time for LED 0. */
  fullMs = $state(4);
  /** The full dose as energy, mJ/cm², or null when it is set as a time. */
  doseMJcm2 = $state<number | null>(null);
  /** The Order list's choice: `auto`, the default, is the fastest order for the drawing (issue 28). */
  strategy = $state<OrderChoice>('auto');
  /** Every order's estimate for the drawing as the preview last planned it, µs, and the fastest of them. */
  orderEstimates = $state.raw<Record<StrategyName, number> | null>(null);
  fastest = $state<StrategyName>('scan');
  /** The order a job made now runs in: the choice, or for `auto` the fastest the preview found (checked again before it runs). */
  get order(): StrategyName {
    return this.strategy === 'auto' ? this.fastest : this.strategy;
  }
  /** The last dry run's findings, and the job they were found for. */
  check = $state.raw<{ findings: Finding[]; job: PrintJob; duty: number[] } | null>(null);
  /** The dry run under way (in a worker: a whole bed's takes seconds): what it checks and how far it has got. */
  checking = $state.raw<{ what: string; stage: string } | null>(null);
  #stopCheck: AbortController | null = null;
  /** The question the user has not answered yet; nothing moves or lights until they do. */
  pending = $state.raw<Pending | null>(null);
  error = $state<string | null>(null);
  /** Each LED's share of the running job's time lit, from its dry run; null for a job not checked here. */
  duty = $state<number[] | null>(null);
  /** What the running job counts: passes on the move (scan), stops, or both (mixed: a pass on the move or a stop is one step). */
  runningUnit = $state<'pass' | 'stop' | 'step'>('stop');
  /** The estimates the user was shown for the job started here (with its paced time when one was offered). */
  runningEstimate = $state.raw<JobEstimate | null>(null);
  /** The job started here runs paced: started so, or continued so after a pause to cool. */
  runningPaced = $state(false);
  /** The job started here last, with the settings it was planned with: the delivered-dose map plans its cells from it. */
  ran = $state.raw<{ job: PrintJob; config: MachineConfig; linkBaud: number } | null>(null);
  /** The movement that waits for the homing under way ("Jog X"), said with the homing's sign. */
  afterHoming = $state<string | null>(null);

  /** Called before every job starts (the project is kept then); set by the app. */
  beforeJob: () => Promise<void> = async () => {};

  constructor(private readonly printer: Printer, private readonly editor: () => GridEditor) {}

  /** What may be done to the machine now, and why not (job/actions.ts): every control reads it. */
  get actions(): Actions {
    return actionsFor(viewOf(this.printer));
  }

  /** The estimate the running job is held to: paced when it runs paced (job-times.ts). */
  get runningEstimateUs(): number | null {
    return estimateUsFor(this.runningEstimate, this.runningPaced || !!this.printer.device.job?.paced);
  }

  /** The connected machine's settings, else the Mega's defaults. */
  get config(): MachineConfig {
    return this.printer.config ?? DEFAULT_CONFIG;
  }

  /** The printhead link's speed the estimates price: the connected printer's (`Cap:LINK_BAUD`), else BOARD_LINK_BAUD. */
  get linkBaud(): number {
    return this.printer.linkBaud;
  }

  /** The LEDs' irradiance from the printer's settings, or why a dose in mJ/cm² cannot be used. */
  get calibration(): Calibration {
    return calibrationOf(this.printer.config);
  }

  /** Sets the full dose in mJ/cm² (null: as a time); the time kept beside it is LED 0's. */
  setDoseMJcm2(mJcm2: number | null): void {
    this.doseMJcm2 = mJcm2;
    const c = this.calibration;
    if (mJcm2 !== null && 'irradianceUWcm2' in c) this.fullMs = msFor(mJcm2, c.irradianceUWcm2[0]);
  }

  /** The drawing as a job for this machine, or null when nothing is drawn. */
  job(): PrintJob | null {
    return this.#jobOf(this.editor().composed());
  }

  /** The same, a few ms a task: a whole bed composed, then bounded, takes tens of ms each. */
  async jobSoon(): Promise<PrintJob | null> {
    const composed = await this.editor().composedSoon(nextTask);
    await nextTask();
    return this.#jobOf(composed, await composed.boundsSoon(nextTask));
  }

  #jobOf(grid: DoseGrid, bounds = grid.bounds()): PrintJob | null {
    const ed = this.editor();
    return jobFromGrid(grid, ed.machine, {
      dose: doseOf(this.fullMs, this.doseMJcm2, this.calibration),
      strategy: { name: this.order },
      leds: ledsOf(this.config),
    }, undefined, bounds);
  }

  /** The dry run, then the question: the time, where it lands, the verdict. Nothing fires before the yes. */
  exposeDrawing = () =>
    this.#act(async () => {
      this.#gate('expose');
      const ed = this.editor();
      this.checking = { what: 'drawing', stage: 'drawing the objects' };
      await ed.layer.settled().finally(() => (this.checking = null)); // rasters made in a worker
      const job = await this.jobSoon();
      if (!job) throw new Error('nothing is drawn');
      await nextTask();
      const { cutsOf } = await import('../studio/objects/clipping');
      const { twoSidedBoards } = await import('../studio/objects/board-object');
      await this.#ask('drawing', job, cutsOf(ed.layer.objects, (o) => ed.layer.raster(o), ed.grid.cols, ed.grid.rows, ed.machine.pitchUm), twoSidedBoards(ed.layer.objects));
    });

  /** From the question: the job exposes only this side of a two-sided board (the others left out), checked again. */
  exposeOnlySide = async (board: TwoSided, id: number) => {
    const { onlySide } = await import('../studio/objects/board-object');
    this.pending = null;
    this.editor().layer.updateEach(onlySide(board, id), 'one side in the job');
    await this.exposeDrawing();
  };

  /** The test pattern at the full dose set here, checked and asked about like a drawing. */
  exposeTestPattern = () =>
    this.#act(async () => {
      this.#gate('expose');
      const { testPattern } = await import('../device/test-pattern');
      await this.#ask('test pattern', { ...testPattern(1), dose: doseOf(this.fullMs, this.doseMJcm2, this.calibration), strategy: { name: this.order } });
    });

  /** The user accepts that the cut objects' parts off the bed are not exposed. */
  acceptCuts = async () => {
    const p = this.pending;
    if (p?.kind !== 'expose') return;
    const { clippingFinding } = await import('../studio/dry-run');
    this.pending = { ...p, accepted: true, findings: p.findings.map((f) => (f.check === 'clipping' ? clippingFinding(p.cuts, true) : f)) };
  };

  /**
   * The pending exposure's dry run, its machine line read live: the printhead answering again (the
   * app asks every 2 s while E30 stands), a head that cooled or one that got hot changes the verdict
   * while the question is open.
   */
  get findings(): Finding[] {
    const p = this.pending;
    if (p?.kind !== 'expose') return [];
    return p.findings.map((f) => (f.check === 'machine' ? machineFinding(this.#machineNow()) : f));
  }

  /** The machine as its reports leave it: after checkPrinthead, an E30 stands exactly when the printhead did not answer. */
  #machineNow() {
    const device = this.printer.device;
    return machineNow(device.activeFaults, device.deciC, limitsOf(this.config));
  }

  /** The user's yes to what is pending (an exposure without errors, or a homing). */
  confirm = (opts: { paced?: boolean } = {}) =>
    this.#act(async () => {
      const p = this.pending;
      const findings = this.findings;
      this.pending = null;
      if (!p) return;
      // The machine may have turned busy while the question was open: it is asked again here.
      this.#gate(p.kind === 'expose' ? 'expose' : 'move');
      if (p.kind === 'home-first') {
        this.afterHoming = p.what;
        try {
          await this.printer.send('G28');
        } finally {
          this.afterHoming = null;
        }
        await p.run();
      } else if (!findings.some((f) => f.level === 'error')) {
        const paced = !!opts.paced && p.pacedUs !== null;
        this.runningEstimate = { estimateUs: p.estimateUs, pacedUs: p.pacedUs };
        this.runningPaced = paced;
        await this.#run(p.job, p.duty, paced);
      }
    });

  cancel = () => {
    this.pending = null;
  };

  /**
   * A head movement the user asked for (go to, jog, frame, a probe touch). A machine that may not be
   * homed must home first, every axis to its endstop: the user is told and agrees before it moves.
   */
  move = (what: string, run: () => Promise<unknown>) => {
    const gate = this.actions.move;
    if (!gate.open) return void (this.error = `${what}: not now: ${gate.why}`);
    // A Home still running counts: the printer runs lines in order, so this move follows it.
    if (this.printer.homed === true || this.printer.homing > 0) this.#act(run);
    else this.pending = { kind: 'home-first', what, homed: this.printer.homed, run };
  };

  /** The head goes round where the drawing will land, LEDs off. */
  frame = () => {
    const job = this.job();
    if (!job) {
      this.error = 'nothing is drawn';
      return;
    }
    const gate = this.actions.frame;
    if (!gate.open) return void (this.error = `Frame: not now: ${gate.why}`);
    this.move('Frame', async () => {
      const { framingMoves } = await import('./framing');
      await this.printer.moves(framingMoves(job, num(this.config, 'speed.travel')));
    });
  };

  act = (f: () => Promise<unknown>) => this.#act(f);

  /** Continues a job paused to cool, paced from here on: its times are then the paced forecast's. */
  continuePaced = () =>
    this.#act(async () => {
      this.#gate('continuePaced');
      await this.printer.resumePaced();
      this.runningPaced = true;
    });

  /** Throws, to be shown as the action's error, when the rule keeps `action` closed: a click is never dropped silently. */
  #gate(action: Action): void {
    const gate = this.actions[action];
    if (!gate.open) throw new Error(`Not now: ${gate.why}`);
  }

  /** Stops the dry run under way: no question follows. */
  stopCheck = () => this.#stopCheck?.abort();

  async #ask(what: 'drawing' | 'test pattern', asked: PrintJob, cuts?: Cut[], boards: TwoSided[] = []): Promise<void> {
    const leveling = await this.printer.leveling();
    await this.printer.checkPrinthead();
    const device = this.printer.device;
    const startC = device.deciC?.map((d) => d / 10) ?? null;
    const machine = this.#machineNow();
    const { checkJob, Cancelled } = await import('../work/check-job');
    await nextTask();
    const stop = (this.#stopCheck = new AbortController());
    this.checking = { what, stage: 'starting' };
    let summary;
    try {
      // In the worker: for `auto`, the fastest order for exactly this job (of those on the bed), whatever the preview last saw; then the dry run.
      summary = await checkJob(
        { job: asked, config: $state.snapshot(this.config), auto: this.strategy === 'auto', jobFormat: this.printer.jobFormat, linkBaud: this.printer.linkBaud, opts: $state.snapshot({ leveling: leveling.on, mesh: leveling.mesh, startC, cuts, boards, machine }) },
        { signal: stop.signal, onProgress: (p) => (this.checking = { what, stage: p.stage }) },
      );
    } catch (e) {
      if (e instanceof Cancelled) return;
      throw e;
    } finally {
      this.checking = null;
      this.#stopCheck = null;
    }
    const { findings, duty, estimateUs, pacedUs, upload } = summary;
    const rate = this.printer.uploadRate;
    const job = { ...asked, strategy: { name: summary.order } };
    this.check = { findings, job, duty };
    const mm = (um: number) => Math.round(um) / 1000;
    const areaMm = {
      x0: mm(job.originUm.x), y0: mm(job.originUm.y),
      x1: mm(job.originUm.x + job.grid.cols * job.pitchUm.x), y1: mm(job.originUm.y + job.grid.rows * job.pitchUm.y),
    };
    this.pending = { kind: 'expose', what, job, findings, duty, estimateUs, pacedUs, upload, rate, uploadUs: uploadUs(uploadBytes(upload, rate), rate), areaMm, cuts: cuts ?? [], accepted: false, boards };
  }

  async #run(job: PrintJob, duty: number[] | null, paced: boolean): Promise<void> {
    JobNotice.askPermission(); // from the click that starts the job: its end can reach the desktop
    this.duty = duty;
    this.runningUnit = job.strategy.name === 'scan' ? 'pass' : job.strategy.name === 'mixed' ? 'step' : 'stop';
    await this.beforeJob();
    // The last job's reports are not this one's: its map starts empty, through its upload too.
    this.printer.dose.clear();
    this.printer.doseRevision++;
    this.ran = { job, config: $state.snapshot(this.config), linkBaud: this.linkBaud };
    await this.printer.send('G28');
    await this.printer.startJob(job, { paced });
  }

  async #act(f: () => Promise<unknown>): Promise<void> {
    this.error = null;
    try {
      await f();
    } catch (e) {
      this.error = (e as Error).message;
    }
  }
}
