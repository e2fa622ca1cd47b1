// The simulated Mega: protocol/mega.md over a byte stream, with motion, the printhead link, probing,
// the SD job lifecycle and configuration, in virtual time.

import { meshZ, type Mesh } from '../planner/mesh';
import { parseCommand, formatMilli, type Command } from '../protocol/dialect-command';
import { DIALECT_MAX_LINE } from '../protocol/dialect-frame';
import { LineReceiver } from '../protocol/dialect-receiver';
import { formatReply, type JobState } from '../protocol/dialect-reply';
import { errorByCode } from '../protocol/errors';
import { JobVerifier } from '../protocol/job-verify';
import { LineSplitter } from '../protocol/line-splitter';
import { FAULT, parseNanoReply } from '../protocol/nano';
import { bedZ, type BedShape } from './bed';
import type { VirtualClock } from './clock';
import { CONFIG_DEFAULTS, num, validConfig } from './config';
import { JobRunner } from './job-runner';
import { JobStream, type StreamError } from './job-stream';
import { Motion, type Xyz } from './motion';
import type { NanoModel } from './nano-model';
import { resumeVerdict } from './resume';
import type { SdCard } from './sd-card';

const WINDOW = 4;
const POLL_US = 500_000;
const KEEPALIVE_US = 2_000_000;
/** Commands still obeyed between the records of a stream (M828), so a running stream can be watched and paused. */
const STREAM_COMMANDS = /^(M24|M25|M524|M27|M105|M114|M115|M155|M154)\b/i;

type Handler = (c: Command, done: () => void) => void;

export interface MegaOptions {
  firmwareName: string;
  bed: BedShape;
  /** The EEPROM as the last power cycle left it. */
  eeprom?: Record<string, string> | null;
}

export class MegaModel {
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
  #splitter = new LineSplitter(DIALECT_MAX_LINE);
  #receiver: LineReceiver;
  #queue: { body: string; n?: number }[] = [];
  #busy = false;
  #upload: { file: string; verifier: JobVerifier; lines: string[] } | null = null;
  #stream: JobStream | null = null;
  #selected = '';
  #reports = { temp: 0, pos: 0, job: 0 };
  #reportTimers: Record<string, ReturnType<VirtualClock['at']> | null> = { temp: null, pos: null, job: null };
  #jog: number | null = null;
  #missedPolls = 0;
  #faultsShown = 0;
  #handlers: Record<string, Handler>;

  constructor(
    private readonly clock: VirtualClock,
    private readonly nano: NanoModel,
    private readonly sd: SdCard,
    private readonly emitBytes: (bytes: string) => void,
    private readonly o: MegaOptions,
  ) {
    this.motion = new Motion(clock, this.config);
    this.job = new JobRunner(clock, this.motion, nano, sd, this.config, (s) => this.#jobChanged(s), (code, message) => {
      if (code === 31) this.#faultsShown |= FAULT.OVERTEMP; // the background poll won't say it again
      this.line(`FAULT:E${code} ${message}`);
    });
    this.job.onProgress = () => this.#stream?.progress();
    this.#receiver = new LineReceiver({ movesFree: () => this.motion.movesFree, windowFree: () => WINDOW - this.#queue.length });
    this.#handlers = this.#commands();
    this.eeprom = o.eeprom ?? null;
    this.#loadConfig();
  }

  boot(): void {
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
        this.#pump();
      }
    }
  }

  // --- the command queue --------------------------------------------------------------------------

  #pump(): void {
    while (!this.#busy && this.#queue.length) {
      const { body, n } = this.#queue[0];
      this.#busy = true;
      let pumping = true;
      this.#run(body, n, () => {
        this.#queue.shift();
        this.#receiver.markAnswered(n);
        this.line(this.#receiver.ok(n)); // names the line it answers, never a merely queued one
        this.#busy = false;
        if (!pumping) this.#pump(); // a long command ended: the lines queued behind it run now
      });
      pumping = false;
    }
  }

  #run(body: string, n: number | undefined, done: () => void): void {
    // Records never start with G or M and a digit, so commands still run between an upload's
    // records. A plain line there is not a record: on a noisy wire it is most likely the tail of a
    // numbered line that a damaged byte split (mega.md §5 M28).
    const command = /^[GM]\d/i.test(body);
    if ((this.#upload || this.#stream) && n === undefined && !command) {
      return this.#error(4, done, 'a job record needs a line number');
    }
    if (this.#upload && !command) return this.#uploadRecord(body, done);
    // A stream that has ended (aborted, failed) reads the rest of its records and drops them; a command
    // (records never start with G or M and a digit) shows its host has moved on, so the stream is over.
    if (this.#stream && !this.#stream.live && /^[GM]\d/i.test(body) && !/^M29\b/i.test(body)) this.#stream = null;
    if (this.#stream && !/^M29\b/i.test(body) && !STREAM_COMMANDS.test(body)) {
      const stream = this.#stream;
      return this.#long(done, (finish) => {
        stream.push(body, finish);
        if (stream.holding) this.line('busy: processing'); // at once: the host must not take the wait for a lost line
      });
    }
    const parsed = parseCommand(body);
    if (!parsed.ok) return this.#error(parsed.error, done, parsed.error === 10 ? body.split(' ')[0] : undefined);
    const c = parsed.command;
    if (this.halted && c.word !== 'M999' && c.word !== 'M112') return this.#error(13, done);
    const h = this.#handlers[c.word];
    if (!h) return this.#error(10, done, c.word);
    h(c, done);
  }

  #error(code: number, done: () => void, detail?: string): void {
    this.#errorLine(code, detail);
    done();
  }

  #errorLine(code: number, detail?: string): void {
    this.line(`Error:E${code} ${errorByCode(code)!.message}${detail ? `: ${detail}` : ''}`);
  }

  /** A long command: keep-alive lines while it runs, done when `until` calls back. */
  #long(done: () => void, until: (finish: () => void) => void): void {
    let alive = this.clock.after(KEEPALIVE_US, function tick(this: MegaModel) {
      this.line('busy: processing');
      alive = this.clock.after(KEEPALIVE_US, tick.bind(this));
    }.bind(this));
    until(() => {
      this.clock.cancel(alive);
      done();
    });
  }

  // --- commands -----------------------------------------------------------------------------------

  #commands(): Record<string, Handler> {
    const p = (c: Command) => ('params' in c ? c.params : {});
    const text = (c: Command) => ('text' in c ? c.text : '');
    const mm = (v: number | null | undefined) => (typeof v === 'number' ? v : null); // already µm (milli-mm)
    return {
      M115: (_c, done) => {
        this.line(formatReply({ kind: 'firmware', name: this.o.firmwareName, protocol: 1 }));
        for (const [k, v] of [['RX_WINDOW', WINDOW], ['AUTOREPORT_TEMP', 1], ['AUTOREPORT_POS', 1], ['SDCARD', this.sd.present ? 1 : 0], ['RESUME', 1]] as const) {
          this.line(`Cap:${k}:${v}`);
        }
        done();
      },
      M105: (_c, done) => {
        if (!this.nano.present) return this.#error(30, done);
        this.line(this.#temps());
        done();
      },
      M155: (c, done) => this.#autoReport('temp', p(c).S, done),
      M154: (c, done) => {
        const ms = p(c).P;
        if (typeof ms === 'number') return this.#autoReport('pos', ms >= 50000 ? ms / 1000 : -1, done, true);
        this.#autoReport('pos', p(c).S, done);
      },
      M27: (c, done) => {
        if ('S' in p(c)) return this.#autoReport('job', p(c).S, done);
        this.line(this.#jobLine());
        done();
      },
      M117: (c, done) => {
        this.message = ('text' in c ? c.text : '').slice(0, 16); // the panel's last row
        done();
      },
      M821: (_c, done) => {
        // The model runs each command in zero virtual time: no loop is ever late, nothing is dropped.
        this.line('echo:DIAG loop_max_us=0 step_isr_max_us=0 underruns=0 rx_dropped=0 tx_dropped=0');
        done();
      },
      M114: (_c, done) => {
        this.line(this.#positionLine());
        done();
      },
      M119: (_c, done) => {
        const pos = this.motion.now();
        const at = (i: number) => (this.motion.homed[i] && pos[i] === 0 ? 'TRIGGERED' : 'open');
        this.line(`x_min: ${at(0)}`);
        this.line(`y_min: ${at(1)}`);
        this.line(`z_min: ${at(2)}`);
        this.line(`z_probe: ${this.nano.touching ? 'TRIGGERED' : 'open'}`);
        done();
      },
      G90: (_c, done) => ((this.absolute = true), done()),
      G91: (_c, done) => ((this.absolute = false), done()),
      G0: (c, done) => this.#move(c, done),
      G1: (c, done) => this.#move(c, done),
      G4: (c, done) => {
        const ms = typeof p(c).P === 'number' ? p(c).P! / 1000 : typeof p(c).S === 'number' ? p(c).S! : 0;
        this.clock.after(ms * 1000, done);
      },
      G28: (c, done) => this.#home(c, done),
      M17: (_c, done) => ((this.motion.enabled = true), done()),
      M18: (_c, done) => (this.motion.release(), done()),
      M84: (_c, done) => (this.motion.release(), done()),
      M410: (_c, done) => (this.#stopJog(), this.motion.stop(), done()),
      M820: (c, done) => this.#jogStart(c, done),
      M822: (c, done) => this.#selfTest('Q' in p(c) ? 'quick' : 'full', done),
      M401: (_c, done) => this.#probeServo('D', done),
      M402: (_c, done) => this.#probeServo('U', done),
      M280: (c, done) => {
        const s = p(c).S;
        const op = s === 10000 ? 'D' : s === 90000 ? 'U' : s === 160000 ? 'X' : null;
        if (p(c).P !== 0 || !op) return this.#error(11, done);
        this.#probeServo(op, done);
      },
      G30: (_c, done) => this.#probeHere(done, () => done()),
      G29: (c, done) => this.#level(c, done),
      M420: (c, done) => {
        if ('V' in p(c)) {
          if (!this.mesh) return this.#error(11, done, 'no mesh');
          this.#meshLines().forEach((l) => this.line(l));
        }
        if (typeof p(c).S === 'number') {
          if (p(c).S && !this.mesh) return this.#error(11, done, 'no mesh');
          this.leveling = p(c).S !== 0;
        } else if (!('V' in p(c))) this.line(`echo:leveling ${this.leveling ? 'on' : 'off'}`);
        done();
      },
      M355: (c, done) => ((this.light = (p(c).S ?? 0) !== 0), done()),
      M20: (_c, done) => {
        if (!this.sd.present) return this.#error(20, done);
        this.line('Begin file list');
        for (const [name, size] of this.sd.list()) this.line(`${name} ${size}`);
        this.line('End file list');
        done();
      },
      M28: (c, done) => {
        if (!this.sd.present) return this.#error(20, done);
        if (this.#jobActive()) return this.#error(12, done);
        this.#upload = { file: text(c), verifier: new JobVerifier(), lines: [] };
        this.job.state = 'uploading';
        this.line(`echo:Writing to file: ${text(c)}`);
        done();
      },
      M29: (_c, done) => (this.#stream ? this.#endStream(done) : this.#endUpload(done)),
      M828: (_c, done) => {
        if (this.#jobActive()) return this.#error(12, done);
        if (!this.motion.homed[0] || !this.motion.homed[1]) return this.#error(14, done, 'home first (G28)');
        if (this.#tooHot()) return this.#error(31, done, 'printhead faulted');
        this.#stream = new JobStream(this.job, this.job.machine(this.motion.now()), (e) => this.#recordError(e));
        this.line('echo:Streaming: exposed as it arrives, no resume');
        this.job.beginStream('stream');
        done();
      },
      M23: (c, done) => {
        if (!this.sd.files.has(text(c))) return this.#error(21, done, text(c));
        if (this.#jobActive()) return this.#error(12, done);
        this.#selected = text(c);
        this.line(`File opened: ${text(c)} Size: ${this.sd.files.get(text(c))!.length}`);
        this.line('File selected');
        if (!this.job.load(text(c))) return this.#error(24, done);
        done();
      },
      M24: (_c, done) => {
        if (this.job.state === 'paused') {
          if (this.#tooHot()) return this.#error(31, done, 'printhead still faulted');
          this.job.resume();
          return done();
        }
        if (!this.#selected || !this.job.plan) return this.#error(26, done);
        if (this.job.state === 'running') return this.#error(12, done);
        if (this.#tooHot()) return this.#error(31, done, 'printhead faulted');
        if (!this.motion.homed[0] || !this.motion.homed[1]) return this.#error(14, done, 'home first (G28)');
        if (this.job.state !== 'ready') this.job.load(this.#selected);
        this.job.start(0);
        done();
      },
      M25: (_c, done) => (this.job.pause(), done()),
      M524: (_c, done) => {
        if (this.#upload) {
          this.#upload = null; // an upload in progress is given up: nothing is kept (mega.md M524)
          this.job.state = 'aborted';
        }
        this.job.abort();
        this.motion.stop();
        done();
      },
      M30: (c, done) => {
        if (!this.sd.files.delete(text(c))) return this.#error(21, done, text(c));
        if (this.#selected === text(c)) this.#selected = '';
        done();
      },
      M1000: (c, done) => {
        const cp = this.sd.checkpoint;
        if ('S' in p(c)) {
          this.line(cp ? `JOB:interrupted file=${cp.file} stop=${cp.done}/${cp.stops}` : 'JOB:idle');
          return done();
        }
        if ('C' in p(c)) {
          this.sd.checkpoint = null;
          return done();
        }
        if (!cp) return this.#error(27, done);
        if (!this.motion.homed[0] || !this.motion.homed[1]) return this.#error(14, done, 'home first (G28)');
        if (!this.job.load(cp.file)) return this.#error(21, done, cp.file);
        this.#selected = cp.file;
        const { from, verdict } = resumeVerdict(cp, parseNanoReply(this.nano.command('C\n') ?? ''));
        this.job.start(from);
        this.line(`echo:resume: stop ${cp.done} ${verdict}`);
        done();
      },
      M850: (c, done) => {
        const [key, value] = text(c).split(/\s+/);
        if (!(key in CONFIG_DEFAULTS)) return this.#error(50, done, key);
        if (value === undefined) {
          this.line(`M850 ${key} ${this.config[key]}`);
          return done();
        }
        if (!validConfig(key, value)) return this.#error(50, done, `${key} ${value}`);
        this.config[key] = value;
        done();
      },
      M500: (_c, done) => {
        if (this.job.state === 'running') return this.#error(12, done);
        this.eeprom = { ...this.config };
        if (!this.sd.present) {
          this.line('echo:Settings stored in EEPROM only: no SD card');
          return done();
        }
        this.sd.files.set('CONFIG.TXT', Object.entries(this.config).map(([k, v]) => `${k} = ${v}\n`).join(''));
        this.line('echo:Settings stored');
        done();
      },
      M501: (_c, done) => {
        if (this.job.state === 'running') return this.#error(12, done);
        this.#loadConfig();
        done();
      },
      M502: (_c, done) => (Object.assign(this.config, CONFIG_DEFAULTS), done()),
      M503: (_c, done) => {
        for (const [k, v] of Object.entries(this.config)) this.line(`M850 ${k} ${v}`);
        done();
      },
      M112: (_c, done) => done(), // already acted on at arrival
      M999: (_c, done) => ((this.halted = false), done()),
      M110: (_c, done) => this.#error(11, done),
    };
    void mm;
  }

  // --- motion -------------------------------------------------------------------------------------

  #move(c: Command, done: () => void): void {
    const p = 'params' in c ? c.params : {};
    const target = [...this.motion.now()] as Xyz;
    const base = this.#queuedTarget();
    for (const [i, a] of (['X', 'Y', 'Z'] as const).entries()) {
      const v = p[a];
      if (v === undefined) continue;
      if (v === null) return this.#error(11, done);
      if (!this.motion.homed[i]) return this.#error(14, done, a);
      target[i] = this.absolute ? v : base[i] + v;
    }
    for (const [i, a] of (['X', 'Y', 'Z'] as const).entries()) {
      if (p[a] === undefined) target[i] = base[i];
      if (target[i] < 0 || target[i] > this.motion.max(i)) return this.#error(15, done, a);
    }
    const feed = typeof p.F === 'number' ? p.F / 1000 / 60 : num(this.config, 'speed.travel');
    const go = () => {
      this.motion.enqueue(target, feed);
      this.#lastTarget = target;
      done();
    };
    if (this.motion.movesFree > 0) go();
    else this.motion.whenIdle(go); // queue full: the line waits, as on the Mega
  }

  #lastTarget: Xyz | null = null;
  #queuedTarget(): Xyz {
    return this.motion.moving && this.#lastTarget ? [...this.#lastTarget] : this.motion.now();
  }

  #home(c: Command, done: () => void): void {
    const p = 'params' in c ? c.params : {};
    const all = !('X' in p) && !('Y' in p) && !('Z' in p);
    const axes = [0, 1, 2].filter((i) => all || ['X', 'Y', 'Z'][i] in p);
    this.#long(done, (finish) => {
      this.motion.whenIdle(() => {
        const from = this.motion.now();
        const to = [...from] as Xyz;
        for (const i of axes) to[i] = 0;
        // Unknown positions home from as far as the axis reaches; the back-off adds 2 × 2 mm slowly.
        const start = from.map((v, i) => (this.motion.homed[i] ? v : this.motion.max(i))) as Xyz;
        const t = this.motion.duration(start, to, num(this.config, 'speed.home')) + 2 * this.motion.duration([0, 0, 0], [2000, 2000, 2000], 5);
        this.clock.after(t, () => {
          this.motion.pos = to;
          for (const i of axes) this.motion.homed[i] = true;
          this.motion.enabled = true;
          finish();
        });
      });
    });
  }

  #jogStart(c: Command, done: () => void): void {
    const p = 'params' in c ? c.params : {};
    const axis = (['X', 'Y', 'Z'] as const).findIndex((a) => typeof p[a] === 'number');
    if (axis < 0 || Math.abs(p[['X', 'Y', 'Z'][axis]]!) !== 1000) return this.#error(11, done);
    if (!this.motion.homed[axis]) return this.#error(14, done);
    const dir = p[['X', 'Y', 'Z'][axis]]! > 0 ? 1 : -1;
    const speed = num(this.config, p.S === 1000 ? 'speed.jog_fast' : 'speed.jog_slow');
    this.motion.stop();
    const to = this.motion.now();
    to[axis] = dir > 0 ? this.motion.max(axis) : 0;
    this.motion.enqueue(to, speed);
    this.#jog = axis;
    done();
  }

  #stopJog(): void {
    this.#jog = null;
  }

  #selfTest(mode: 'quick' | 'full', done: () => void): void {
    if (!this.motion.homed[0] || !this.motion.homed[1]) return this.#error(14, done, 'home first (G28)');
    this.#long(done, (finish) => {
      const reach = mode === 'full' ? [this.motion.max(0), this.motion.max(1)] : [20000, 20000];
      const there: Xyz = [reach[0], reach[1], this.motion.pos[2]];
      this.motion.enqueue(there, num(this.config, 'speed.travel'));
      this.motion.enqueue([0, 0, this.motion.pos[2]], num(this.config, 'speed.home'));
      this.motion.whenIdle(() => {
        const steps = (i: number) => Math.round((reach[i] / 1000) * num(this.config, i ? 'steps_per_mm.y' : 'steps_per_mm.x'));
        this.line(`TEST:${mode} x=pass x_steps=${steps(0)} y=pass y_steps=${steps(1)}`);
        finish();
      });
    });
  }

  // --- probe and mesh -------------------------------------------------------------------------------

  #nanoSay(line: string): string | null {
    const r = this.nano.command(line + '\n');
    if (!this.nano.present) this.#missed();
    return r;
  }

  #probeServo(op: 'D' | 'U' | 'X', done: () => void): void {
    if (!this.nano.present) return this.#error(30, done);
    this.#nanoSay(op);
    this.clock.after(300_000, () => {
      if (this.nano.probe === 'alarm') {
        this.line('PROBE:alarm');
        return this.#error(40, done);
      }
      this.line(op === 'D' ? 'PROBE:deployed' : 'PROBE:stowed');
      done();
    });
  }

  /** Lowers Z until the pin touches the bed at the current X/Y; reports `Bed X: Y: Z:`. */
  #probeHere(done: () => void, then: (zUm: number) => void): void {
    if (!this.motion.homed[2] || !this.motion.homed[0] || !this.motion.homed[1]) return this.#error(14, done, 'home first (G28)');
    if (this.nano.probe !== 'deployed') return this.#error(this.nano.probe === 'alarm' ? 40 : 41, done, 'deploy the probe (M401)');
    this.motion.whenIdle(() => {
      const at = this.motion.now();
      const surface = bedZ(this.o.bed, at[0], at[1]);
      const from = at[2];
      const dz = Math.abs(from - surface) + 2000;
      const t = this.motion.duration([0, 0, 0], [0, 0, dz], 4);
      this.clock.after(t, () => {
        this.nano.touching = true;
        this.nano.trigger();
        this.motion.pos = [at[0], at[1], surface];
        const lift: Xyz = [at[0], at[1], surface + 5000];
        this.line(formatReply({ kind: 'probePoint', um: [at[0], at[1], surface] }));
        this.nano.touching = false;
        this.motion.enqueue(lift, num(this.config, 'speed.z'));
        this.motion.whenIdle(() => then(surface));
      });
    });
  }

  #level(c: Command, done: () => void): void {
    const p = 'params' in c ? c.params : {};
    const nx = typeof p.X === 'number' ? p.X / 1000 : num(this.config, 'mesh.nx');
    const ny = typeof p.Y === 'number' ? p.Y / 1000 : num(this.config, 'mesh.ny');
    if (!Number.isInteger(nx) || !Number.isInteger(ny) || nx < 3 || nx > 9 || ny < 3 || ny > 9) return this.#error(11, done);
    const margin = num(this.config, 'mesh.margin') * 1000;
    const x0 = margin, y0 = margin;
    const dx = Math.floor((this.motion.max(0) - 2 * margin) / (nx - 1));
    const dy = Math.floor((this.motion.max(1) - 2 * margin) / (ny - 1));
    const z: number[][] = Array.from({ length: ny }, () => new Array<number>(nx).fill(0));
    this.#long(done, (finish) => {
      const points: [number, number][] = [];
      for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) points.push([i, j]);
      const nextPoint = (k: number) => {
        if (k === points.length) {
          this.mesh = { nx, ny, x0, y0, dx, dy, z };
          this.leveling = true;
          this.sd.files.set('MESH.TXT', JSON.stringify(this.mesh));
          this.#meshLines().forEach((l) => this.line(l));
          return finish();
        }
        const [i, j] = points[k];
        const i2 = j % 2 ? nx - 1 - i : i; // serpentine over the grid
        this.motion.enqueue([x0 + i2 * dx, y0 + j * dy, this.motion.pos[2]], num(this.config, 'speed.travel'));
        this.#probeHere(finish, (zUm) => {
          z[j][i2] = zUm;
          nextPoint(k + 1);
        });
      };
      nextPoint(0);
    });
  }

  #meshLines(): string[] {
    const m = this.mesh!;
    return [
      `MESH:grid ${m.nx} ${m.ny} x0=${formatMilli(m.x0)} y0=${formatMilli(m.y0)} dx=${formatMilli(m.dx)} dy=${formatMilli(m.dy)}`,
      ...m.z.map((row, j) => `MESH:row ${j} ${row.map(formatMilli).join(' ')}`),
    ];
  }

  /** Cells a stream (M828) holds in its bounded buffer right now. */
  get streamHeldCells(): number {
    return this.#stream?.heldCells ?? 0;
  }

  /** Mesh Z at a bed position while leveling is on, µm. */
  zOffset(x: number, y: number): number {
    return this.leveling && this.mesh ? meshZ(this.mesh, x, y) : 0;
  }

  // --- uploads --------------------------------------------------------------------------------------

  #uploadRecord(record: string, done: () => void): void {
    const u = this.#upload!;
    const before = u.verifier.error;
    const err = u.verifier.push(record);
    if (err && !before) this.#recordError(err);
    u.lines.push(record);
    done();
  }

  #recordError(err: StreamError): void {
    this.#errorLine(err.code, `${err.line ? `line ${err.line}: ` : ''}${err.message}`);
  }

  #endStream(done: () => void): void {
    const err = this.#stream!.finish();
    this.#stream = null;
    if (err) return this.#error(err.code, done, err.message);
    this.line('echo:Stream complete.');
    done();
  }

  #endUpload(done: () => void): void {
    const u = this.#upload;
    if (!u) return this.#error(11, done, 'not uploading');
    this.#upload = null;
    const err = u.verifier.error ?? u.verifier.finish();
    if (err) {
      this.job.state = 'failed';
      return this.#error(err.code, done, err.message); // a partial or unverified upload is never stored
    }
    this.sd.files.set(u.file, u.lines.map((l) => l + '\n').join(''));
    this.job.state = 'idle';
    this.line('echo:Done saving file.');
    done();
  }

  // --- reports, faults, the printhead link ----------------------------------------------------------

  #temps(): string {
    const limits = [0, 1, 2, 3, 4, 5].map((i) => num(this.config, `thermal.limit.${i}`) * 10);
    return formatReply({ kind: 'temps', deciC: this.nano.deciC(), limitDeciC: limits });
  }

  #positionLine(): string {
    const pos = this.motion.now();
    const steps = pos.map((v, i) => Math.round((v / 1000) * num(this.config, ['steps_per_mm.x', 'steps_per_mm.y', 'steps_per_mm.z'][i]))) as Xyz;
    return formatReply({ kind: 'position', um: pos, steps });
  }

  #jobLine(): string {
    const j = this.job;
    if (j.state === 'idle' || !j.plan) return formatReply({ kind: 'job', state: j.state, fields: {} });
    const fields: Record<string, string> = {
      file: j.file,
      stop: `${j.done}/${j.plan.count}`,
      elapsed: String(Math.floor((this.clock.now - j.startedAtUs) / 1e6)),
      ...(j.planComplete ? { remaining: String(Math.round(j.remainingUs() / 1e6)) } : {}), // unknown mid-stream
      leds: String(this.nano.lit),
    };
    if (j.reason) fields.reason = j.reason;
    if (j.streaming) fields.mode = 'stream';
    return formatReply({ kind: 'job', state: j.state, fields });
  }

  #autoReport(kind: 'temp' | 'pos' | 'job', seconds: number | null | undefined, done: () => void, ms = false): void {
    if (typeof seconds !== 'number' || seconds < 0 || seconds > 60000) return this.#error(11, done);
    const periodUs = ms ? seconds * 1000 : seconds * 1000; // S is in thousandths of a second
    this.#reports[kind] = periodUs;
    this.clock.cancel(this.#reportTimers[kind]);
    if (periodUs > 0) {
      const tick = () => {
        this.line(kind === 'temp' ? this.#temps() : kind === 'pos' ? this.#positionLine() : this.#jobLine());
        this.#reportTimers[kind] = this.clock.after(this.#reports[kind], tick);
      };
      this.#reportTimers[kind] = this.clock.after(periodUs, tick);
    }
    done();
  }

  #jobActive(): boolean {
    return this.job.state === 'running' || this.job.state === 'paused' || this.#upload !== null || this.#stream !== null;
  }

  #jobChanged(state: JobState): void {
    this.line(this.#jobLine());
    void state;
    this.#stream?.progress(); // a paused, continued or aborted stream answers its waiting record
  }

  #activeFaults(): number {
    const r = this.nano.command('E\n');
    const e = r ? parseNanoReply(r) : null;
    return e && e.op === 'E' ? e.flags & (FAULT.OVERTEMP | FAULT.SENSOR) : 0;
  }

  /** Background poll of the printhead, as the Mega does every 500 ms: faults stop the job. */
  #poll(): void {
    this.clock.after(POLL_US, () => this.#poll());
    const r = this.#nanoSay('E');
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
  }

  /** A hard fault on the Nano, or any sensor at or over the Mega's soft limit: no exposure may start. */
  #tooHot(): boolean {
    if (this.#activeFaults()) return true;
    return this.nano.deciC().some((v, i) => v >= num(this.config, `thermal.limit.${i}`) * 10);
  }

  /** The Mega's own, lower limits (config thermal.limit.*): pause before the Nano has to cut. */
  #softLimits(): void {
    if (this.job.state !== 'running') return;
    const t = this.nano.deciC();
    const over = t.findIndex((v, i) => v >= num(this.config, `thermal.limit.${i}`) * 10);
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
    this.nano.command('R\n');
    this.nano.allOff();
    this.motion.stop();
    this.job.abort();
    if (this.#upload) this.job.state = 'failed';
    this.#upload = null; // an upload or a stream in progress is over; its remaining records get errors
    this.#stream = null;
  }

  /** The defaults, then the EEPROM copy, then every good line of CONFIG.TXT (firmware/mega/CONFIG.md). */
  #loadConfig(): void {
    Object.assign(this.config, CONFIG_DEFAULTS, this.eeprom ?? {});
    const text = this.sd.present ? this.sd.files.get('CONFIG.TXT') : undefined;
    if (!text) return;
    for (const line of text.split('\n')) {
      const m = /^\s*([a-z0-9_.]+)\s*=\s*(\S+)\s*$/.exec(line);
      if (m && validConfig(m[1], m[2])) this.config[m[1]] = m[2];
    }
  }
}
