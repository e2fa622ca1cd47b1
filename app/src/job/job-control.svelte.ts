// The job the studio's drawing becomes, and what happens before and while it runs: the exposure
// settings, the dry run that must pass before any LED fires, framing with the LEDs off, and the run.

import type { Printer } from '../device/connection.svelte';
import type { PrintJob, StrategyName } from '../protocol/job-types';
import { num } from '../sim/config';
import { dryRun, type Finding } from '../studio/dry-run';
import type { GridEditor } from '../studio/editor.svelte';
import { jobFromGrid } from '../studio/grid-job';
import { DEFAULT_CONFIG, ledsOf, type MachineConfig } from '../studio/machine-config';
import { framingMoves } from './framing';
import { JobNotice } from './job-notice.svelte';

export class JobControl {
  /** The exposure of a cell at 100 % dose, ms. */
  fullMs = $state(4);
  strategy = $state<StrategyName>('serpentine');
  /** The last dry run's findings, and the job they were found for. */
  check = $state.raw<{ findings: Finding[]; job: PrintJob; duty: number[] } | null>(null);
  error = $state<string | null>(null);
  /** Each LED's share of the running job's time lit, from its dry run; null for a job not checked here. */
  duty = $state<number[] | null>(null);

  /** Called before every job starts (the project is kept then); set by the app. */
  beforeJob: () => Promise<void> = async () => {};

  constructor(private readonly printer: Printer, private readonly editor: () => GridEditor) {}

  /** The connected machine's settings, else the Mega's defaults. */
  get config(): MachineConfig {
    return this.printer.config ?? DEFAULT_CONFIG;
  }

  /** The drawing as a job for this machine, or null when nothing is drawn. */
  job(): PrintJob | null {
    const ed = this.editor();
    return jobFromGrid(ed.composed(), ed.machine, {
      dose: { map: 'linear', fullUs: Math.round(this.fullMs * 1000) },
      strategy: { name: this.strategy },
      leds: ledsOf(this.config),
    });
  }

  /** Dry run first; errors stop here, warnings wait for `exposeAnyway`. */
  exposeDrawing = () =>
    this.#act(async () => {
      const job = this.job();
      if (!job) throw new Error('nothing is drawn');
      const leveling = await this.printer.leveling();
      const { findings, duty } = dryRun(job, this.config, { leveling: leveling.on, mesh: leveling.mesh });
      this.check = { findings, job, duty };
      if (findings.some((f) => f.level !== 'ok')) return;
      await this.#run(job, duty);
    });

  exposeAnyway = () => this.#act(async () => this.check && this.#run(this.check.job, this.check.duty));

  /** The head goes round where the drawing will land, LEDs off. */
  frame = () =>
    this.#act(async () => {
      const job = this.job();
      if (!job) throw new Error('nothing is drawn');
      await this.printer.moves(framingMoves(job, num(this.config, 'speed.travel')));
    });

  act = (f: () => Promise<unknown>) => this.#act(f);

  async #run(job: PrintJob, duty: number[] | null): Promise<void> {
    JobNotice.askPermission(); // from the click that starts the job: its end can reach the desktop
    this.duty = duty;
    await this.beforeJob();
    await this.printer.send('G28');
    await this.printer.startJob(job);
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
