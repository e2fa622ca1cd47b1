// The simulated Mega: protocol/mega.md over a byte stream. This file is the line queue, the dispatch and the
// background work (printhead poll, faults, emergency stop); each command family has its own file.

import { meshZ, type Mesh } from '../planner/mesh';
import { parseCommand, type Command } from '../protocol/dialect-command';
import { DIALECT_MAX_LINE } from '../protocol/dialect-frame';
import { LineReceiver } from '../protocol/dialect-receiver';
import { type JobState } from '../protocol/dialect-reply';
import { errorClass, formatError } from '../protocol/errors';
import { LineSplitter } from '../protocol/line-splitter';
import { FAULT, parseNanoReply } from '../protocol/nano';
import type { BedShape } from './bed';
import type { Clock } from './clock';
import { CONFIG_DEFAULTS, num, validConfig } from './config';
import type { CardPrint, GcodeUpload } from './card-gcode';
import { infoCommands, jobLine } from './mega-info';
import { jobCommands, type JobUpload } from './mega-jobs';
import { motionCommands } from './mega-motion';
import { probeCommands } from './mega-probe';
import { JobRunner } from './job-runner';
import type { JobStream } from './job-stream';
import { Motion } from './motion';
import type { NanoModel } from './nano-model';
import { overSoftLimit } from './pacing';
import type { SdCard } from './sd-card';

const WINDOW = 3;
const POLL_US = 500_000;
/** Commands still obeyed between the records of a stream (M828), so a running stream can be watched and paused. */
const STREAM_COMMANDS = /^(M24|M25|M524|M27|M105|M114|M115|M155|M154)\b/i;
/** Lines a G-code file on the card may not run (mega.md "G-code files on the card"). */
const CARD_REFUSED = /^(M0*23|M0*24|M0*28|M0*29|M0*32|M828|M1000)\b/i;

/** Runs one command; calls `done` once, when its reply block may end. */
export type Handler = (c: Command, done: () => void) => void;

export interface MegaOptions {
  firmwareName: string;
  bed: BedShape;
  /** The EEPROM as the last power cycle left it. */
  eeprom?: Record<string, string> | null;
}

export class MegaModel {
  static readonly WINDOW = WINDOW;
  readonly motion: Motion;
  readonly job: JobRunner;
  config: Record<string, string> = { ...CONFIG_DEFAULTS };
  /** The EEPROM copy M500 makes; it outlives a power cycle with the rest of the model. */
  eeprom: Record<string, string> | null = null;
  mesh: Mesh | null = null;
  leveling = false;
  light = false;
  /** The panel's message line (M117). */
  message = '';
  halted = false;
  absolute = true;
  /** G0/G1's feed rate, mm/s: modal as Marlin's, until the next F; null until one is given (the configured travel speed). */
  feedMmS: number | null = null;
  /** The `busy:` interval (M113), µs; 0 sends none. */
  keepaliveUs = 2_000_000;
  /** A job upload (M28 of a job file) or a G-code upload (M28 of a .gco). */
  upload: JobUpload | null = null;
  gcodeUpload: GcodeUpload | null = null;
  stream: JobStream | null = null;
  /** The selected job file (M23). */
  selected = '';
  /** The selected G-code file, running or not (M23, M24, M32). */
  cardPrint: CardPrint | null = null;
  #splitter = new LineSplitter(DIALECT_MAX_LINE);
  #receiver: LineReceiver;
  #queue: { body: string; n?: number }[] = [];
  #busy = false;
  #missedPolls = 0;
  #faultsShown = 0;
  #handlers: Record<string, Handler>;

  constructor(
    readonly clock: Clock,
    readonly nano: NanoModel,
    readonly sd: SdCard,
    private readonly emitBytes: (bytes: string) => void,
    readonly o: MegaOptions,
  ) {
    this.motion = new Motion(clock, this.config);
    this.job = new JobRunner(clock, this.motion, nano, sd, this.config, (s) => this.#jobChanged(s), (code, message) => {
      if (code === 31) this.#faultsShown |= FAULT.OVERTEMP; // the background poll won't say it again
      this.line(`FAULT:E${code} ${message}`);
    });
    this.job.onProgress = () => this.stream?.progress();
    this.job.thermal = { reading: () => this.reading, limits: () => this.#limitsDeciC() };
    this.#receiver = new LineReceiver({ movesFree: () => this.motion.movesFree, windowFree: () => WINDOW - this.#queue.length });
    this.#handlers = { ...infoCommands(this), ...motionCommands(this), ...probeCommands(this), ...jobCommands(this) };
    this.eeprom = o.eeprom ?? null;
    this.loadConfig();
  }

  boot(): void {
    this.nano.command('R\n'); // a reset never leaves an LED on (mega.md §6)
    this.line('start');
    this.#poll();
  }

  line(text: string): void {
    this.emitBytes(text + '\n');
  }

  receive(bytes: string): void {
    for (const l of this.#splitter.push(bytes)) {
      // M112 acts the moment it arrives, ahead of anything queued (protocol/mega.md).
      if (/(^|\s)M112(\s|\*|$)/i.test(l.text.replace(/^N\d+\s+/, ''))) this.#emergency();
      const a = this.#receiver.accept(l);
      if (a.kind === 'reply') a.lines.forEach((t) => this.line(t));
      else if (a.kind === 'execute') {
        this.#queue.push({ body: a.body, n: a.n });
        this.pump();
      }
    }
  }

  // --- the command queue --------------------------------------------------------------------------

  /** Runs queued host lines, then, when none wait, the next line of a G-code file from the card. */
  pump(): void {
    while (!this.#busy) {
      if (this.#queue.length) {
        const { body, n } = this.#queue[0];
        this.#runOne(body, n, () => {
          this.#queue.shift();
          this.#receiver.markAnswered(n);
          this.line(this.#receiver.ok(n)); // names the line it answers, never a merely queued one
        });
        continue;
      }
      const next = this.cardPrint?.next();
      if (next === undefined || next === null) return;
      if (next === 'end') {
        this.cardPrint = null; // Marlin deselects the file once it has run
        this.line('Done printing file');
        return;
      }
      // A file never starts another file or job from inside itself.
      if (CARD_REFUSED.test(next)) this.errorLine(12, next.split(' ')[0]);
      else this.#runOne(next, undefined, () => {});
    }
  }

  #runOne(body: string, n: number | undefined, after: () => void): void {
    this.#busy = true;
    let pumping = true;
    this.#run(body, n, () => {
      after();
      this.#busy = false;
      if (!pumping) this.pump(); // a long command ended: the lines queued behind it run now
    });
    pumping = false;
  }

  #run(body: string, n: number | undefined, done: () => void): void {
    // A G-code upload stores every line of its port but M29 (mega.md "G-code files on the card").
    if (this.gcodeUpload && !/^M29\b/i.test(body)) {
      if (n === undefined) return this.error(4, done, 'a stored line needs a line number');
      this.gcodeUpload.lines.push(body);
      return done();
    }
    // Records never start with G or M and a digit, so commands still run between an upload's
    // records. A plain line there is not a record: on a noisy wire it is most likely the tail of a
    // numbered line that a damaged byte split (mega.md §5 M28).
    const command = /^[GM]\d/i.test(body);
    if ((this.upload || this.stream) && n === undefined && !command) {
      return this.error(4, done, 'a job record needs a line number');
    }
    if (this.upload && !command) return this.#uploadRecord(body, done);
    // A stream that has ended (aborted, failed) reads the rest of its records and drops them; a command
    // (records never start with G or M and a digit) shows its host has moved on, so the stream is over.
    if (this.stream && !this.stream.live && command && !/^M29\b/i.test(body)) this.stream = null;
    if (this.stream && !/^M29\b/i.test(body) && !STREAM_COMMANDS.test(body)) {
      const stream = this.stream;
      return this.long(done, (finish) => {
        stream.push(body, finish);
        if (stream.holding) this.line('busy: processing'); // at once: the host must not take the wait for a lost line
      });
    }
    const parsed = parseCommand(body);
    if (!parsed.ok) return this.error(parsed.error, done, parsed.error === 10 ? body.split(' ')[0] : undefined);
    const c = parsed.command;
    if (this.halted && c.word !== 'M999' && c.word !== 'M112') return this.error(13, done);
    const h = this.#handlers[c.word];
    if (!h) return this.error(10, done, c.word);
    h(c, done);
  }

  /** Prints the error's line (by its class, mega.md §2) and ends the block. */
  error(code: number, done: () => void, detail?: string): void {
    this.errorLine(code, detail);
    if (errorClass(code) === 'fault' && this.cardPrint?.running) this.cardPrint = null; // a file does not run on past a fault
    done();
  }

  errorLine(code: number, detail?: string): void {
    this.line(formatError(code, detail));
  }

  /** A long command: keep-alive lines while it runs, done when `until` calls back. */
  long(done: () => void, until: (finish: () => void) => void): void {
    let alive: ReturnType<Clock['after']> | null = null;
    const tick = () => {
      this.line('busy: processing');
      alive = this.clock.after(this.keepaliveUs, tick);
    };
    if (this.keepaliveUs > 0) alive = this.clock.after(this.keepaliveUs, tick);
    until(() => {
      this.clock.cancel(alive);
      done();
    });
  }

  /** Cells a stream (M828) holds in its bounded buffer right now. */
  get streamHeldCells(): number {
    return this.stream?.heldCells ?? 0;
  }

  /** Mesh Z at a bed position while leveling is on, µm. */
  zOffset(x: number, y: number): number {
    return this.leveling && this.mesh ? meshZ(this.mesh, x, y) : 0;
  }

  jobActive(): boolean {
    return this.job.state === 'running' || this.job.state === 'paused' || this.upload !== null || this.gcodeUpload !== null ||
      this.stream !== null || !!this.cardPrint?.running;
  }

  #uploadRecord(record: string, done: () => void): void {
    const u = this.upload!;
    const before = u.verifier.error;
    const err = u.verifier.push(record);
    if (err && !before) this.errorLine(err.code, `${err.line ? `line ${err.line}: ` : ''}${err.message}`);
    u.lines.push(record);
    done();
  }

  #jobChanged(state: JobState): void {
    this.line(jobLine(this));
    void state;
    this.stream?.progress(); // a paused, continued or aborted stream answers its waiting record
  }

  // --- the printhead link and faults ---------------------------------------------------------------

  nanoSay(line: string): string | null {
    const r = this.nano.command(line + '\n');
    if (!this.nano.present) this.#missed();
    return r;
  }

  /** The printhead's temperatures as the Mega last read them (T, every 500 ms), 0.1 °C. */
  reading: number[] = [];

  #limitsDeciC(): number[] {
    return this.reading.map((_, i) => num(this.config, `thermal.limit.${i}`) * 10);
  }

  #activeFaults(): number {
    const r = this.nano.command('E\n');
    const e = r ? parseNanoReply(r) : null;
    return e && e.op === 'E' ? e.flags & (FAULT.OVERTEMP | FAULT.SENSOR) : 0;
  }

  /** Background poll of the printhead, as the Mega does every 500 ms: faults stop the job. */
  #poll(): void {
    this.clock.after(POLL_US, () => this.#poll());
    if (this.nano.present) this.reading = this.nano.deciC();
    const r = this.nanoSay('E');
    if (!r) return;
    this.#missedPolls = 0;
    const e = parseNanoReply(r);
    if (!e || e.op !== 'E') return;
    const active = e.flags & (FAULT.OVERTEMP | FAULT.SENSOR | FAULT.CUTOFF);
    if (active & (FAULT.OVERTEMP | FAULT.CUTOFF) && !(this.#faultsShown & FAULT.OVERTEMP)) {
      const t = this.nano.deciC();
      const hot = t.indexOf(Math.max(...t));
      this.line(`FAULT:E31 over-temperature T${hot} ${(t[hot] / 10).toFixed(1)}`);
      this.job.faulted('overtemp');
    }
    this.#faultsShown = active & FAULT.OVERTEMP;
    this.#softLimits();
    this.job.reading();
  }

  /** A hard fault on the Nano, or any sensor at or over the Mega's soft limit: no exposure may start. */
  tooHot(): boolean {
    if (this.#activeFaults()) return true;
    return this.nano.deciC().some((v, i) => v >= num(this.config, `thermal.limit.${i}`) * 10);
  }

  /** The Mega's own, lower limits (config thermal.limit.*): pause before the Nano has to cut. */
  #softLimits(): void {
    if (this.job.state !== 'running') return;
    const t = this.reading;
    const over = overSoftLimit(t, this.#limitsDeciC());
    if (over < 0) return;
    this.line(`FAULT:E31 over-temperature T${over} ${(t[over] / 10).toFixed(1)} (soft limit)`);
    this.job.faulted('overtemp');
  }

  #missed(): void {
    if (++this.#missedPolls === 3) {
      this.line('FAULT:E30 printhead not responding');
      this.job.faulted('printhead');
    }
  }

  #emergency(): void {
    this.halted = true;
    this.feedMmS = null; // Marlin's M112 ends in a reset, which forgets the F
    this.nano.command('R\n');
    this.nano.allOff();
    this.motion.stop();
    this.job.abort();
    if (this.upload) this.job.state = 'failed';
    this.upload = null; // an upload or a stream in progress is over; its remaining records get errors
    this.gcodeUpload = null; // a G-code upload cut short leaves no file
    this.stream = null;
    this.cardPrint = null;
  }

  /** The defaults, then the EEPROM copy, then every good line of CONFIG.TXT (firmware/mega/CONFIG.md). */
  loadConfig(): void {
    Object.assign(this.config, CONFIG_DEFAULTS, this.eeprom ?? {});
    const text = this.sd.present ? this.sd.files.get('CONFIG.TXT') : undefined;
    if (!text) return;
    for (const line of text.split('\n')) {
      const m = /^\s*([a-z0-9_.]+)\s*=\s*(\S+)\s*$/.exec(line);
      if (m && validConfig(m[1], m[2])) this.config[m[1]] = m[2];
    }
  }
}
