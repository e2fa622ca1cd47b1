// The simulated printer: the firmware's own C++ (the Mega's command core and the Nano's printhead
// logic, compiled to WebAssembly: wasm/printer-module.ts) with the physics the firmware does not
// hold around it, each written once: virtual time, the head's thermal model (head-thermal.ts, which
// the dry run's forecast also runs), the bed the probe touches (bed.ts), and the faults the
// simulator's panel injects on the link and the printhead. The stepper timing, the switches and the
// LEDs' on-time are the module's (firmware/virtual/mega_rig.h).
// Runs in a Web Worker (the app's default device) and in Node (tests, `npm run sim` for desktop hosts).

import { bedZ, DEFAULT_BED, type BedShape } from './bed';
import { VirtualClock } from './clock';
import { HEAD_THERMAL, HeadThermal, type HeadThermalModel } from '../machine/head-thermal';
import { FaultyLink, type LinkFaults } from './link-faults';
import { saneFaults, withLinkFaults, type SimFaults } from './sim-faults';
import { firmwareModule } from './wasm/firmware-module';
import { PrinterModule } from './wasm/printer-module';

/** What outlives the page that ran the simulated printer (sim-snapshot.ts keeps it in the browser). */
export interface SavedMachine {
  /** The card's files, the job's checkpoint (JOB~CKP) among them. */
  files: [string, string][];
  /** The Mega's EEPROM as the firmware left it; null for a blank one. */
  eeprom: Uint8Array | null;
  /** Power-ups so far: the Nano's start counter, which its firmware keeps in its EEPROM. */
  boots: number;
}

export interface SimOptions {
  /** Resting temperature of each sensor, tenths of °C. */
  ambientDeciC?: number[];
  /** The head's thermal model, over the one the dry run also reads. */
  thermal?: Partial<HeadThermalModel>;
  bed?: BedShape;
  link?: LinkFaults;
  /** No printhead answers. */
  missingNano?: boolean;
  /** The probe goes into alarm on its next deploy. */
  probeAlarm?: boolean;
  noSd?: boolean;
  /** The card, EEPROM and start count of an earlier run of this machine. */
  saved?: SavedMachine | null;
}

/** The module runs at most this long between looks at the host's timers and its own output: one
 *  main-loop pass, so a reply leaves when the firmware writes it (at 1 ms slices the lost time
 *  showed in P1: 76.6 % of the line at 1 ms one-way latency, against 96.9 % at 200 µs). */
const SLICE_US = 100;
/** The main loop's pass (mega_rig.h): the module's time moves in whole passes. */
const PASS_US = 100;
/** How often the TMP36s are read afresh from the thermal model. */
const READING_US = 20_000;

export class SimPrinter {
  readonly clock = new VirtualClock();
  readonly module: PrinterModule;
  readonly thermal: HeadThermal;
  #linkFaults: LinkFaults;
  #link: FaultyLink;
  #faults: SimFaults;
  #stallUntil = 0;
  #held = '';
  #disconnected = false;
  /** The module's own time, µs: ahead of the clock by less than a pass. */
  #moduleUs = 0;
  #readAt = 0;
  /** Up to when the thermal model has run, µs of the module's time. */
  #heatedUs = 0;
  #onUs = [0, 0, 0, 0];
  onDisconnect: () => void = () => {};

  /** `emit` receives every byte the Mega sends on its USB port. */
  constructor(private readonly emit: (bytes: string) => void, o: SimOptions = {}) {
    const bed = o.bed ?? DEFAULT_BED;
    this.module = new PrinterModule(firmwareModule(), { bedUm: (x, y) => bedZ(bed, x, y) });
    const ambientC = o.ambientDeciC?.map((d) => d / 10) ?? HEAD_THERMAL.ambientC;
    this.thermal = new HeadThermal({ ...HEAD_THERMAL, ...o.thermal, ambientC });
    this.#linkFaults = { ...o.link };
    this.#link = new FaultyLink(this.#linkFaults);
    this.#faults = saneFaults({ ...o.link, overheatCPerS: o.thermal?.extraHeatingCPerS, probeAlarm: o.probeAlarm, missingNano: o.missingNano });
    // Power-up, with what an earlier run left on the card and in the EEPROMs.
    const m = this.module;
    m.start();
    const saved = o.saved;
    for (const [name, text] of saved?.files ?? []) m.putFile(name, text);
    if (saved?.eeprom) m.setEeprom(saved.eeprom);
    m.starts = saved?.boots ?? 0;
    this.#powerUp();
    m.cardInserted(!o.noSd);
    this.setFaults({ probeAlarm: this.#faults.probeAlarm });
  }

  /** The whole machine starts afresh from its card and EEPROMs, the Nano's start count one more. */
  #powerUp(): void {
    this.module.reset(true);
    this.#onUs = [0, 1, 2, 3].map((i) => this.module.onUs(i));
    this.#readTemps();
    this.module.sentBytes(0); // nobody listens yet: `start` is said again when a host opens the port
    this.module.sentBytes(1);
  }

  /** Power-ups so far, this one included. */
  get boots(): number {
    return this.module.starts;
  }

  get faults(): SimFaults {
    return { ...this.#faults };
  }

  /** Changes the faults while the printer runs (the simulated printer's panel). */
  setFaults(faults: Partial<SimFaults>): void {
    const f = (this.#faults = saneFaults({ ...this.#faults, ...faults }));
    this.#linkFaults = withLinkFaults(this.#linkFaults, f);
    this.#link = new FaultyLink(this.#linkFaults);
    this.module.nanoMissing(f.missingNano);
    this.#heat();
    this.thermal.model.extraHeatingCPerS = f.overheatCPerS;
    // For the next deploy: the alarm release disarms it, as the panel's box stays as set.
    if (faults.probeAlarm !== undefined) this.module.probeAlarm(f.probeAlarm);
  }

  /** The USB cable comes out now: the printer runs on, nothing passes until a host opens the link again. */
  unplug(): void {
    this.#linkFaults = { ...this.#linkFaults, disconnectAfterMs: this.clock.now / 1000 };
  }

  /** A host opened the USB port: DTR resets the Mega alone, its card and EEPROM kept, the Nano running on. */
  resetMega(): void {
    this.#disconnected = false;
    this.module.reset(false);
  }

  /** The port is open: the Mega restarts and prints `start`, as after any host's DTR. */
  boot(): void {
    this.resetMega();
  }

  /** Power cycle: what is in RAM is lost; the card and the EEPROMs keep theirs. */
  powerCycle(): void {
    this.#disconnected = false;
    this.#powerUp();
  }

  /** Bytes from the host. */
  receive(bytes: string): void {
    if (this.#disconnected) return;
    const passed = this.#link.pass(bytes);
    if (this.clock.now < this.#stallUntil) this.#held += passed;
    else if (passed) this.module.receive(0, passed);
  }

  /** Advances virtual time by `ms`. */
  advance(ms: number): void {
    this.advanceTo(this.clock.now + ms * 1000);
  }

  /** Real-time hosts: advance to `nowMs` since the start. */
  tick(nowMs: number): void {
    this.advanceTo(nowMs * 1000);
  }

  get disconnected(): boolean {
    return this.#disconnected;
  }

  /** Advances virtual time to `us`: the machine, its physics and the host's timers together. */
  advanceTo(us: number): void {
    const f = this.#linkFaults;
    if (f.disconnectAfterMs !== undefined && !this.#disconnected && us >= f.disconnectAfterMs * 1000) {
      this.#runTo(f.disconnectAfterMs * 1000);
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
    this.#runTo(us);
    if (this.#held && this.clock.now >= this.#stallUntil) {
      const held = this.#held;
      this.#held = '';
      this.module.receive(0, held);
    }
  }

  #runTo(us: number): void {
    while (this.clock.now < us) {
      const to = Math.min(us, this.clock.next, this.clock.now + SLICE_US);
      if (to > this.#moduleUs) {
        const step = Math.ceil((to - this.#moduleUs) / PASS_US) * PASS_US;
        this.module.run(step);
        this.#moduleUs += step;
        this.#heat();
        if (this.#moduleUs >= this.#readAt) this.#readTemps();
        const out = this.module.sentBytes(0);
        if (out && !this.#disconnected) this.emit(this.#link.pass(out));
        this.module.sentBytes(1); // the ESP's port: nobody on it here
      }
      this.clock.advanceTo(Math.max(to, this.clock.now));
    }
  }

  /** The LEDs' light since the last look heats the head, each LED by its share of the time lit. */
  #heat(): void {
    const dt = this.#moduleUs - this.#heatedUs;
    if (dt <= 0) return;
    this.#heatedUs = this.#moduleUs;
    const duty = [0, 1, 2, 3].map((i) => {
      const on = this.module.onUs(i);
      const share = (on - this.#onUs[i]) / dt;
      this.#onUs[i] = on;
      return Math.max(0, Math.min(1, share));
    });
    this.thermal.advanceDuty(dt, duty);
  }

  #readTemps(): void {
    this.module.temps(this.thermal.deciC());
    this.#readAt = this.#moduleUs + READING_US;
  }

  /** The sensors as the thermal model has them now, 0.1 °C. */
  deciC(): number[] {
    return this.thermal.deciC();
  }

  /**
   * A page that ran this printer went away while a job from its card ran: a real printer would have
   * run on, with no host listening. The page's worker ended with it, so this machine takes the job
   * up at its checkpoint as the firmware resumes any job (G28 and M1000, on the ESP's port where
   * nobody listens), and runs for `ms` of its time, or until the job ends (`budgetMs` of real
   * time at most). The page that comes back opens the link, which resets the Mega as any host's
   * does: the job waits at its checkpoint for the resume.
   */
  runOn(ms: number, paced: boolean, budgetMs = 5000): void {
    this.#disconnected = true; // nobody listens on USB while it runs on
    this.module.command(1, 'G28'); // the resume needs the axes homed
    this.module.command(1, paced ? 'M1000 P1' : 'M1000');
    const end = this.clock.now + Math.max(0, ms) * 1000;
    const stopAt = performance.now() + budgetMs; // a runaway page must not hang its worker on a week-long job
    let started = false;
    while (this.clock.now < end && performance.now() < stopAt) {
      this.#runTo(Math.min(end, this.clock.now + 100_000));
      const job = this.module.cardJob();
      if (job) started = true;
      else if (started || this.clock.now > 120e6) break; // it ended, or never took up (2 min of homing at most)
    }
  }

  /** What a reload keeps. */
  saved(): SavedMachine {
    return { files: this.module.card(), eeprom: this.module.eeprom(), boots: this.module.starts };
  }
}
