// The simulated printer: the Mega and the Nano models together behind a byte stream, in virtual time.
// Runs in a Web Worker (the app's default device) and in Node (tests, `npm run sim` for desktop hosts).

import { DEFAULT_BED, type BedShape } from './bed';
import { ClockScope, VirtualClock } from './clock';
import { FaultyLink, type LinkFaults } from './link-faults';
import { MegaModel } from './mega';
import type { Xyz } from './motion';
import { DEFAULT_NANO, NanoModel, type NanoOptions } from './nano-model';
import { SdCard, type Checkpoint } from './sd-card';
import { saneFaults, withLinkFaults, type SimFaults } from './sim-faults';

/** What outlives the page that ran the simulated printer (sim-snapshot.ts keeps it in the browser). */
export interface SavedMachine {
  files: [string, string][];
  checkpoint: Checkpoint | null;
  /** The Mega's EEPROM as M500 left it. */
  eeprom: Record<string, string> | null;
  /** Power-ups so far: the Nano's start counter, which the firmware keeps in its EEPROM. */
  boots: number;
}

export interface SimOptions {
  firmwareName?: string;
  /** Resting temperature of each sensor, tenths of °C. */
  ambientDeciC?: number[];
  /** Soft limits the Mega reports, tenths of °C (config thermal.limit.*). */
  limitDeciC?: number[];
  /** A slow ±0.3 °C drift on the temperatures (default on); tests turn it off for exact values. */
  drift?: boolean;
  bed?: BedShape;
  nano?: Partial<NanoOptions>;
  link?: LinkFaults;
  /** No printhead answers. */
  missingNano?: boolean;
  /** The probe goes into alarm on its next deploy. */
  probeAlarm?: boolean;
  noSd?: boolean;
  /** The card, checkpoint, EEPROM and start count of an earlier run of this machine. */
  saved?: SavedMachine | null;
}

export class SimPrinter {
  clock = new VirtualClock();
  readonly sd = new SdCard();
  nano!: NanoModel;
  mega!: MegaModel;
  #linkFaults: LinkFaults;
  #link: FaultyLink;
  #faults: SimFaults;
  #stallUntil = 0;
  #held = '';
  #disconnected = false;
  onDisconnect: () => void = () => {};

  #boots = 0;
  /** `emit` receives every byte the Mega would send. */
  constructor(private readonly emit: (bytes: string) => void, private readonly o: SimOptions = {}) {
    this.#linkFaults = { ...o.link };
    this.#link = new FaultyLink(this.#linkFaults);
    this.#faults = saneFaults({ ...o.link, overheatCPerS: o.nano?.extraHeatingCPerS, probeAlarm: o.probeAlarm, missingNano: o.missingNano });
    this.sd.present = !o.noSd;
    const saved = o.saved;
    if (saved) {
      for (const [name, text] of saved.files) this.sd.files.set(name, text);
      this.sd.checkpoint = saved.checkpoint;
      this.#boots = saved.boots;
    }
    this.#build(saved?.eeprom ?? null);
  }

  /** Power-ups so far, this one included. */
  get boots(): number {
    return this.#boots;
  }

  get faults(): SimFaults {
    return { ...this.#faults };
  }

  /** Changes the faults while the printer runs (the simulated printer's panel). */
  setFaults(faults: Partial<SimFaults>): void {
    const before = this.#faults;
    const f = (this.#faults = saneFaults({ ...before, ...faults }));
    this.#linkFaults = withLinkFaults(this.#linkFaults, f);
    this.#link = new FaultyLink(this.#linkFaults);
    this.nano.present = !f.missingNano;
    this.nano.extraHeatingCPerS = f.overheatCPerS;
    if (faults.probeAlarm !== undefined) this.nano.alarmOnDeploy = faults.probeAlarm; // for the next deploy: the alarm release (X) disarms it
  }

  /** The USB cable comes out now: the printer runs on, nothing passes until a host opens the link again. */
  unplug(): void {
    this.#linkFaults = { ...this.#linkFaults, disconnectAfterMs: this.clock.now / 1000 };
  }

  #build(eeprom: Record<string, string> | null = null): void {
    const nanoOptions: NanoOptions = { ...DEFAULT_NANO, ...this.o.nano };
    if (this.o.ambientDeciC) nanoOptions.ambientDeciC = this.o.ambientDeciC;
    this.nano = new NanoModel(this.clock, nanoOptions);
    this.nano.boot = ++this.#boots; // each power-up is a new start, as the firmware's EEPROM counter says
    this.nano.present = !this.#faults.missingNano;
    this.nano.alarmOnDeploy = this.#faults.probeAlarm;
    this.nano.extraHeatingCPerS = this.#faults.overheatCPerS;
    this.#buildMega(eeprom);
    if (this.o.drift === false) this.nano.temp.forEach((_, i) => (this.nano.temp[i] = nanoOptions.ambientDeciC[i] / 10));
  }

  #megaClock: ClockScope | null = null;
  #buildMega(eeprom: Record<string, string> | null): void {
    this.#megaClock?.close(); // the old Mega's timers (moves, reports, the printhead poll) die with it
    this.#megaClock = new ClockScope(this.clock);
    this.mega = new MegaModel(this.#megaClock, this.nano, this.sd, (b) => this.#out(b), {
      firmwareName: this.o.firmwareName ?? 'UVExposure 0.1.0 (Simulated Mega)',
      bed: this.o.bed ?? DEFAULT_BED,
      eeprom,
    });
    if (this.o.limitDeciC) this.o.limitDeciC.forEach((l, i) => (this.mega.config[`thermal.limit.${i}`] = String(l / 10)));
  }

  /**
   * A host opened the USB port: DTR resets the Mega alone (its RAM, a halt after M112, the line count),
   * while the Nano runs on and the card and the EEPROM keep what they hold. The Mega's reset turns the LEDs off.
   */
  resetMega(): void {
    this.#disconnected = false; // a host has the port open again
    this.#buildMega(this.mega.eeprom);
    this.boot();
  }

  /** Call once the port is open: a real Mega prints `start` after reset. */
  boot(): void {
    this.mega.boot();
  }

  /** Power cycle: RAM state is lost, the SD card (jobs, checkpoint, config) and the EEPROM survive. */
  powerCycle(): void {
    this.#disconnected = false;
    const now = this.clock.now;
    this.clock = new VirtualClock(); // the old models' timers go with the old clock
    this.clock.now = now;
    this.#build(this.mega.eeprom); // the EEPROM survives too
    this.boot();
  }

  /** Bytes from the host. */
  receive(bytes: string): void {
    if (this.#disconnected) return;
    const passed = this.#link.pass(bytes);
    if (this.clock.now < this.#stallUntil) this.#held += passed;
    else this.mega.receive(passed);
  }

  /** Advances virtual time by `ms`, running everything due (tests and fast simulations). */
  advance(ms: number): void {
    this.advanceTo(this.clock.now + ms * 1000);
  }

  /** Advances virtual time to `us` (real-time hosts call this with their clock). */
  advanceTo(us: number): void {
    const f = this.#linkFaults;
    if (f.disconnectAfterMs !== undefined && !this.#disconnected && us >= f.disconnectAfterMs * 1000) {
      this.clock.advanceTo(f.disconnectAfterMs * 1000);
      this.#disconnected = true;
      this.#linkFaults = { ...f, disconnectAfterMs: undefined }; // once: a link opened again stays up
      this.onDisconnect();
      return;
    }
    if (f.stallEveryMs && f.stallMs) {
      // Stalls start on every multiple of stallEveryMs; held bytes are read when one ends.
      const period = f.stallEveryMs * 1000;
      const start = Math.floor(us / period) * period;
      if (us < start + f.stallMs * 1000) this.#stallUntil = start + f.stallMs * 1000;
    }
    this.clock.advanceTo(us);
    if (this.#held && this.clock.now >= this.#stallUntil) {
      const held = this.#held;
      this.#held = '';
      this.mega.receive(held);
    }
  }

  /** Real-time hosts: advance to `nowMs` since the start. */
  tick(nowMs: number): void {
    this.advanceTo(nowMs * 1000);
  }

  get disconnected(): boolean {
    return this.#disconnected;
  }

  /**
   * A page that ran this printer went away mid-job, and its card says where the job stood: a real
   * printer would have run on, with no host to listen. Boots, takes the job up at its checkpoint
   * with the head at `pos`, and runs it for `ms` of the printer's time, or until it ends or stops
   * (`budgetMs` of real time at most). The page that comes back opens the link, which resets the
   * Mega as any host's does (resetMega): the job waits at its checkpoint for the resume.
   */
  runOn(pos: Xyz, ms: number, budgetMs = 5000): void {
    const cp = this.sd.checkpoint;
    this.#disconnected = true; // nobody listens while it runs on
    this.boot();
    if (!cp || !this.mega.job.load(cp.file)) return;
    this.nano.carryOn(cp.boot, cp.fires); // the printhead kept its start too
    const { mega } = this;
    mega.selected = cp.file;
    mega.motion.homed = [true, true, true];
    mega.motion.pos = [...pos];
    mega.motion.enabled = true;
    mega.job.start(cp.done);
    const end = this.clock.now + Math.max(0, ms) * 1000;
    const stopAt = performance.now() + budgetMs; // a runaway page must not hang its worker on a week-long job
    while (mega.job.state === 'running' && this.clock.now < end && performance.now() < stopAt) {
      this.advanceTo(Math.min(end, this.clock.now + 1_000_000));
    }
  }

  #out(bytes: string): void {
    if (this.#disconnected) return;
    this.emit(this.#link.pass(bytes));
  }
}
