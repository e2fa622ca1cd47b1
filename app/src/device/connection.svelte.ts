// The app's one view of the printer: the connection lifecycle as a discriminated union, the device state
// folded from every report, link health, and the job and machine actions the UI calls.

import { LINE_RATE, type LinkRate } from '../job/link-rate';
import type { JobFormat } from '../protocol/job-types';
import { ConsoleLog, type Entry } from '../console/console-log';
import type { Reply } from '../protocol/dialect-reply';
import { formatReply } from '../protocol/reply-format';
import type { PrintJob } from '../protocol/job-types';
import { CommandError } from './command-error';
import type { LinkHealth } from './dialect-client';
import { applyReport, clearFault, emptyState, PRINTHEAD_SILENT, type DeviceState, type JobProgress } from './device-state';
import type { PrinterLink, StartOptions, UploadProgress } from './link';
import { configOf, interruptedOf, levelingOf, type InterruptedJob } from './printer-replies';
import { parseMesh } from './mesh-report';
import { ThermalHistory } from './thermal-history';
import { DoseLedger } from './dose-ledger';
import { DeviceClock } from './device-clock';
import type { Mesh } from '../planner/mesh';
import { linkFor } from './links';
import { lineWork } from './line-work';
import { PickerDismissed } from './serial-support';
export { SIMULATOR_BUILT_IN, loadSimulatorPanel, setSimulatorSpeed, tellSimulator } from './sim-transport';
import type { TransportKind } from './transport';
import { BOARD_LINK_BAUD, linkBaudOf } from '../machine/config';

export type Connection =
  /** `job` is the job the printer ran when the app let go of it (Disconnect): it may still be running. */
  | { state: 'idle'; job?: JobProgress | null }
  | { state: 'connecting'; kind: TransportKind }
  | { state: 'connected'; kind: TransportKind }
  /** The link dropped. `job` is the last progress seen: the printer may still be running it. */
  | { state: 'lost'; kind: TransportKind; error: string; job: JobProgress | null }
  | { state: 'error'; kind: TransportKind; error: string };

export type Upload = { state: 'idle' } | ({ state: 'uploading' } & UploadProgress) | { state: 'failed'; error: string };

export const SENSOR_NAMES = ['LED 0', 'LED 1', 'LED 2', 'LED 3', 'Driver', 'Frame'];

/** The commands whose answer is a line of a kind the printer also sends as an auto-report. */
const REPORT_ANSWERS: Record<string, Reply['kind']> = { M105: 'temps', M114: 'position', M27: 'job' };

function describe(e: unknown): string {
  return e instanceof CommandError ? e.message : e instanceof Error ? e.message : String(e);
}

export class Printer {
  connection = $state<Connection>({ state: 'idle' });
  device = $state<DeviceState>(emptyState());
  health = $state<LinkHealth | null>(null);
  upload = $state<Upload>({ state: 'idle' });
  /** The machine's settings, as `M503` listed them when the link opened (null until then). */
  config = $state<Record<string, string> | null>(null);
  /** Offered for resuming when the link opened; null once resumed, discarded or absent. */
  interrupted = $state<InterruptedJob | null>(null);
  /** Every line to and from the printer, newest last, for the console (not deep-reactive: it is long). */
  readonly log = new ConsoleLog();
  /** Bumped with each line logged, so the console can follow. */
  logRevision = $state(0);
  /** The temperatures of the last 20 minutes (not deep-reactive: the chart reads it on each revision). */
  readonly thermal = new ThermalHistory();
  thermalRevision = $state(0);
  /** What the head delivered to the job, stop by stop, from its DOSE: lines (not deep-reactive: read it on each revision). */
  readonly dose = new DoseLedger();
  doseRevision = $state(0);
  /** The mesh the printer last reported, and the one it had before the last probing, for comparison. */
  mesh = $state<Mesh | null>(null);
  previousMesh = $state<Mesh | null>(null);
  /**
   * Whether the machine is homed, as far as the app knows: false after the link opened a Mega (it
   * restarts) or its motors were released, true after a homing or a move it took, null when unknown
   * (the hub's Mega did not restart). The printer cannot be asked.
   */
  homed = $state<boolean | null>(null);
  /** G28 lines sent and not yet answered: a move sent now runs after them, homed. */
  homing = $state(0);
  /** Probe work in hand (a mesh's M401, G29, M402 as one, or a lone probe line): job/actions.ts closes the rest. */
  probing = $state(0);
  /** Settings being written (M850 with a value, M500–M502, and the M503 that reads them back). */
  configuring = $state(0);
  /** From the click on Resume until the printer runs the job on (M1000 answered): it homes meanwhile. */
  resuming = $state(false);
  /** Printer seconds per wall second of the open link (the simulated printer at ?simSpeed=N runs N×). */
  timeScale = $state(1);
  /**
   * The printhead link's speed the connected printer plans jobs at (`Cap:LINK_BAUD`, mega.md M115:
   * 115200 once its Nano failed a raise), which the estimates price; BOARD_LINK_BAUD when none is
   * connected or it did not say.
   */
  linkBaud = $state(BOARD_LINK_BAUD);
  #link: PrinterLink | null = null;
  /** Bumped by every connect and disconnect: a connect whose link loaded after a newer one gives way. */
  #attempt = 0;
  /** Asks the silent printhead again every few seconds while E30 stands. */
  #printheadWatch: ReturnType<typeof setInterval> | null = null;
  /** The printer's time, which the thermal history is kept in: its rates are per the printer's second. */
  readonly #clock = new DeviceClock();
  /** Error codes an app-made query expects as an answer (no mesh yet): not errors the user must read. */
  readonly #expected = new Map<number, number>();
  /** Each reply's console line, so the lines answering what the user typed can be shown as replies. */
  #logged = new WeakMap<Reply, Entry>();

  constructor(private readonly makeLink: (kind: TransportKind) => PrinterLink | Promise<PrinterLink> = linkFor) {}

  get firmware(): string | null {
    return this.device.firmware;
  }

  /** The job a dropped or closed link left running or paused on the printer, as last seen: it may still be exposing. */
  get leftJob(): JobProgress | null {
    const c = this.connection;
    const job = c.state === 'idle' || c.state === 'lost' ? c.job : null;
    return job && (job.state === 'running' || job.state === 'paused') ? job : null;
  }

  async connect(kind: TransportKind): Promise<void> {
    await this.disconnect();
    this.connection = { state: 'connecting', kind };
    const attempt = ++this.#attempt;
    let link: PrinterLink;
    try {
      link = await this.makeLink(kind); // the link's code may load now
    } catch (e) {
      if (attempt === this.#attempt) this.connection = { state: 'error', kind, error: `its code could not be loaded (${describe(e)})` };
      return;
    }
    if (attempt !== this.#attempt) return; // disconnected or connected elsewhere meanwhile
    this.#link = link;
    this.timeScale = link.timeScale;
    this.homed = kind === 'esp' ? null : false;
    try {
      await link.open((r, line) => this.#onReply(r, line), (error) => {
        if (this.#link !== link) return;
        this.#link = null;
        this.connection = { state: 'lost', kind, error: error?.message ?? 'link closed', job: this.device.job };
      });
      await link.command('M105');
      await link.command('M155 S1');
      await link.command('M154 S1');
      await link.command('M27 S1');
      this.linkBaud = linkBaudOf(link.linkBaud);
      this.config = configOf(await link.command('M503'));
      this.interrupted = interruptedOf(await link.command('M1000 S'));
      if (this.#link === link) {
        this.connection = { state: 'connected', kind };
        this.health = { ...link.health };
      }
    } catch (e) {
      if (this.#link !== link) return;
      this.#link = null;
      if (e instanceof PickerDismissed) {
        this.connection = { state: 'idle' };
        return;
      }
      this.connection = { state: 'error', kind, error: describe(e) };
      await link.close().catch(() => {});
    }
  }

  async disconnect(): Promise<void> {
    this.#attempt++;
    const link = this.#link;
    const c = this.connection;
    const job = link ? this.device.job : c.state === 'lost' || c.state === 'idle' ? (c.job ?? null) : null;
    this.#link = null;
    this.device = emptyState();
    this.health = null;
    this.upload = { state: 'idle' };
    this.config = null;
    this.linkBaud = BOARD_LINK_BAUD;
    this.interrupted = null;
    this.resuming = false;
    this.mesh = this.previousMesh = null;
    if (link) await link.close().catch(() => {});
    this.connection = { state: 'idle', job };
  }

  /** A raw dialect line from the console; resolves with its reply lines. */
  async send(line: string): Promise<Reply[]> {
    if (!this.#link) throw new Error('not connected');
    this.log.add(line, 'sent');
    this.logRevision++;
    const work = lineWork(line);
    if (work) this[work]++;
    try {
      const replies = await this.#link.command(line);
      if (/^(G28|G0|G1)\b/i.test(line)) this.homed = true; // homed, or a move the printer took homed
      else if (/^(M18|M84)\b/i.test(line)) this.homed = false; // released motors forget where they are
      return replies;
    } catch (e) {
      if (e instanceof CommandError && e.code === 14) this.homed = false;
      throw e;
    } finally {
      if (work) this[work]--;
    }
  }

  /**
   * A question the app asks on its own (not the user), where an error with one of `expected` codes
   * is an answer ("no mesh"): it is logged for the debug view, not as an error, and resolves null.
   */
  async ask(line: string, expected: number[]): Promise<Reply[] | null> {
    if (!this.#link) throw new Error('not connected');
    for (const c of expected) this.#expected.set(c, (this.#expected.get(c) ?? 0) + 1);
    try {
      return await this.#link.command(line);
    } catch (e) {
      if (e instanceof CommandError && expected.includes(e.code)) return null;
      throw e;
    } finally {
      for (const c of expected) {
        const n = (this.#expected.get(c) ?? 1) - 1;
        if (n > 0) this.#expected.set(c, n);
        else this.#expected.delete(c);
      }
    }
  }

  /**
   * A line the user typed (the console): its reply block is shown in the log as replies, so M105,
   * M114 or M503 answer there without showing every auto-report.
   */
  async sendTyped(line: string): Promise<Reply[]> {
    const replies = await this.send(line);
    // A block holds every line since the last ok, auto-reports among them: of the report kinds only
    // the one the command answers, and its last line, the one just before the ok, is its reply.
    const answer = REPORT_ANSWERS[line.trim().split(/\s+/)[0].toUpperCase()];
    const own = replies.filter((r) => r.kind === answer).at(-1);
    const entries = own ? [this.#logged.get(own) ?? this.log.add(formatReply(own), 'reply')] : []; // over the ESP, a reply block comes apart from the relayed lines
    this.log.markReplies(entries);
    this.logRevision++;
    return replies;
  }

  /** The job format the connected printer reads (job.md), 1 when none is connected. */
  get jobFormat(): JobFormat {
    return this.#link?.jobFormat ?? 1;
  }

  /** The connected link's upload rate: measured on its last upload, else the line's. */
  get uploadRate(): LinkRate {
    return this.#link?.uploadRate ?? LINE_RATE;
  }

  async startJob(job: PrintJob, opts: StartOptions = {}): Promise<void> {
    const link = this.#link;
    if (!link) throw new Error('not connected');
    try {
      await link.startJob(job, (p) => (this.upload = { state: 'uploading', ...p }), opts);
      this.upload = { state: 'idle' };
    } catch (e) {
      this.upload = { state: 'failed', error: describe(e) };
      throw e;
    }
  }

  /** Homes and runs the interrupted job on from its checkpoint: every cell exposed exactly once. */
  resumeInterrupted = async () => {
    this.resuming = true;
    try {
      await this.send('G28');
      await this.send('M1000');
      this.interrupted = null;
    } finally {
      this.resuming = false;
    }
  };

  /** Asks the printhead's temperatures (M105): afterwards E30 stands in the device state exactly when it did not answer. */
  checkPrinthead = async (): Promise<void> => {
    const answered = (await this.ask('M105', [PRINTHEAD_SILENT])) !== null;
    if (answered && clearFault(this.device, PRINTHEAD_SILENT)) this.device = { ...this.device };
    // An E30 answer stands as the FAULT:E30 report would (one may have come before the app connected), and is asked after.
    if (!answered && !this.device.activeFaults.some((a) => a.code === PRINTHEAD_SILENT)) {
      applyReport(this.device, { kind: 'fault', code: PRINTHEAD_SILENT, message: 'printhead not responding' }, Date.now());
      this.device = { ...this.device };
      this.#watchPrinthead();
    }
  };

  /** The Mega says E30 once, and nothing when the printhead is back: the app asks until it answers. */
  #watchPrinthead(): void {
    if (this.#printheadWatch) return;
    this.#printheadWatch = setInterval(() => {
      if (this.#link && this.device.activeFaults.some((a) => a.code === PRINTHEAD_SILENT)) return void this.checkPrinthead().catch(() => {});
      clearInterval(this.#printheadWatch!);
      this.#printheadWatch = null;
    }, 2000);
  }

  discardInterrupted = async () => {
    await this.send('M1000 C');
    this.interrupted = null;
  };

  /**
   * Lines sent one after another. A move the printer refuses for want of homing (E14) is an error:
   * homing moves every axis to its endstop, so the app asks first (JobControl.move), never silently.
   */
  async moves(lines: string[]): Promise<void> {
    for (const line of lines) await this.send(line);
  }

  /** Deploys the probe, maps the bed on n × n points (`G29`), and stows it. */
  async probeMesh(n: number): Promise<void> {
    const before = this.mesh;
    this.probing++; // one piece of work: nothing slips in between its lines
    try {
      await this.moves(['M401', `G29 X${n} Y${n}`, 'M402']);
    } finally {
      this.probing--;
    }
    if (before && this.mesh !== before) this.previousMesh = before;
  }

  /**
   * Whether exposures follow the mesh (bare `M420`), and the mesh they follow, read from the
   * printer if leveling is on and the app has none yet. Leveling is null if the printer does not say.
   */
  async leveling(): Promise<{ on: boolean | null; mesh: Mesh | null }> {
    const on = levelingOf(await this.send('M420'));
    if (on && !this.mesh) await this.send('M420 V');
    return { on, mesh: this.mesh };
  }

  /** Reads the settings again (`M503`). */
  readConfig = async () => {
    this.config = configOf(await this.send('M503'));
  };

  /** Sets each changed setting (`M850`), then reads them all back; `save` keeps them over a restart (`M500`). */
  async writeConfig(changes: Record<string, string>, save: boolean): Promise<void> {
    this.configuring++;
    try {
      for (const [key, value] of Object.entries(changes)) await this.send(`M850 ${key} ${value}`);
      if (save) await this.send('M500');
    } finally {
      try {
        await this.readConfig();
      } finally {
        this.configuring--;
      }
    }
  }

  pause = () => this.send('M25');
  resume = () => this.send('M24');
  /** Continues paced (mega.md "Pacing"): the printer waits to cool before a stop or a pass instead of pausing again. */
  resumePaced = () => this.send('M24 P1');
  abort = () => this.send('M524');

  #onReply(r: Reply, line: string): void {
    this.#logged.set(r, this.log.add(line, r.kind === 'error' && this.#expected.has(r.code) ? 'link' : undefined));
    this.logRevision++;
    if (r.kind === 'temps') {
      this.thermal.add(this.#clock.nowS(this.timeScale), r.deciC.map((d) => d / 10), this.device.job?.state === 'running');
      this.thermalRevision = this.thermal.revision;
    }
    if (applyReport(this.device, r, Date.now())) this.device = { ...this.device };
    if (r.kind === 'job') this.dose.job(r.state, r.fields.file, this.device.job?.stop);
    if (r.kind === 'dose') {
      this.dose.add(r);
      this.doseRevision++;
    }
    if (r.kind === 'fault' && r.code === PRINTHEAD_SILENT) this.#watchPrinthead();
    if (r.kind === 'other' && r.text.startsWith('MESH:row')) this.mesh = parseMesh(this.device.mesh) ?? this.mesh; // whole with its last row
    if (this.#link) this.health = { ...this.#link.health };
  }
}
