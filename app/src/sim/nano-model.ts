// The simulated printhead Nano: LEDs with timed switch-off, a thermal model, the probe, and protocol/nano.md
// over the same codec the firmware uses.

import { FAULT, formatNanoReply, parseNanoCommand, SENSOR_COUNT, type NanoReply } from '../protocol/nano';
import type { VirtualClock } from './clock';
import { HEAD_THERMAL, HeadThermal } from './head-thermal';
import { NanoPrograms, PASS } from './nano-programs';
import { CHAIN_SILENCE_US, PROGRAM_START_LEAD_US } from '../protocol/scan-program';

export interface NanoOptions {
  /** Resting temperature of each sensor, 0.1 °C. */
  ambientDeciC: number[];
  /** The Nano's own cut-off per sensor, 0.1 °C, and the hysteresis. */
  limitDeciC: number[];
  hysteresisDeciC: number;
  capUs: number;
  /** °C a sensor rises per second with its LED on, and the fraction of the gap to ambient lost per second. */
  heatingCPerS: number;
  coolingPerS: number;
  /** Extra heating to force an over-temperature in tests, °C/s on every LED sensor. */
  extraHeatingCPerS: number;
}

/** The head's thermal constants are the shared model's (head-thermal.ts), which the dry run also reads. */
export const DEFAULT_NANO: NanoOptions = {
  ambientDeciC: HEAD_THERMAL.ambientC.map((c) => Math.round(c * 10)),
  limitDeciC: [600, 600, 600, 600, 600, 600],
  hysteresisDeciC: 50,
  capUs: 10_000_000,
  heatingCPerS: HEAD_THERMAL.heatingCPerS,
  coolingPerS: HEAD_THERMAL.coolingPerS,
  extraHeatingCPerS: HEAD_THERMAL.extraHeatingCPerS,
};

export type ProbePin = 'stowed' | 'deployed' | 'alarm';

export class NanoModel {
  lit = 0;
  /** The sensors, integrated in virtual time with the shared thermal model. */
  readonly thermal: HeadThermal;
  probe: ProbePin = 'stowed';
  /** Set by the Mega model while the deployed pin touches the bed. */
  touching = false;
  /** A fault to inject: the next deploy ends in the alarm state. */
  alarmOnDeploy = false;
  /** A missing Nano answers nothing. */
  present = true;
  /** This start's number (the firmware keeps a counter in EEPROM); the printer sets it at power-up. */
  boot = 1;
  /** Each LED's on-time since power-up, µs: the dose the head has given, whatever switched it. */
  readonly onUs = [0, 0, 0, 0];
  /** Scan programs: loaded by A and K, run by G on the clock (protocol/nano.md "Scan programs"). */
  readonly programs: NanoPrograms;
  #chainEvent: ReturnType<VirtualClock['at']> | null = null;
  /** Told every change of the LEDs a running chain makes (the simulated Mega records a pass's light by it). */
  onChainSwitch: ((mask: number) => void) | null = null;
  /** When the last line arrived: a running chain that hears none for CHAIN_SILENCE_US is cut (nano.md "Scan programs"). */
  #lastLineUs = 0;
  #programLast = false;
  #fires = 0;
  #whole = true;
  #latched = 0;
  #latchedTrigger = false;
  #off: (ReturnType<VirtualClock['at']> | null)[] = [null, null, null, null];
  #lastUs = 0;
  #hot = 0;

  constructor(private readonly clock: VirtualClock, private readonly o: NanoOptions = DEFAULT_NANO) {
    const ambientC = o.ambientDeciC.map((d) => d / 10);
    this.programs = new NanoPrograms(o.capUs);
    this.thermal = new HeadThermal({ ...HEAD_THERMAL, ambientC, heatingCPerS: o.heatingCPerS, coolingPerS: o.coolingPerS, extraHeatingCPerS: o.extraHeatingCPerS });
  }

  /** Temperatures in °C (floating). */
  get temp(): number[] {
    return this.thermal.temp;
  }

  /** °C/s added to each LED's sensor, lit or not: over-temperature on demand (tests, the simulated printer's panel), from now on. */
  get extraHeatingCPerS(): number {
    return this.thermal.model.extraHeatingCPerS;
  }

  set extraHeatingCPerS(c: number) {
    this.#integrate();
    this.thermal.model.extraHeatingCPerS = c;
  }

  /** Takes up the count of a start that never ended (a printer that ran on while its host was away). */
  carryOn(boot: number, fires: number): void {
    this.boot = boot;
    this.#fires = fires;
  }

  /** One command line (with '\n'); returns the reply line, if the command has one. */
  command(line: string): string | null {
    if (!this.present) return null;
    this.#integrate();
    this.#lastLineUs = this.clock.now;
    const text = line.replace(/\r?\n$/, '');
    if (text.startsWith('A:')) {
      if (!this.programs.append(text)) this.#latched |= FAULT.MALFORMED;
      return null;
    }
    if (text.startsWith('K:')) {
      const code = this.programs.seal(text);
      if (code === null) this.#latched |= FAULT.MALFORMED;
      return code === null ? null : formatNanoReply({ op: 'K', code });
    }
    const cmd = parseNanoCommand(text);
    if (!cmd) {
      this.#latched |= FAULT.MALFORMED;
      return null;
    }
    const reply = (r: NanoReply) => formatNanoReply(r);
    switch (cmd.op) {
      case 'S': return reply({ op: 'S', mask: this.lit });
      case 'T': return reply({ op: 'T', deciC: this.deciC() });
      case 'P': {
        const t = this.#latchedTrigger || this.touching;
        this.#latchedTrigger = false;
        return reply({ op: 'P', triggered: t });
      }
      case 'E': {
        const flags = this.#active() | this.#latched;
        this.#latched = 0;
        return reply({ op: 'E', flags });
      }
      case 'V': return reply({ op: 'V', protocol: 1, firmware: '0.2.0-sim' });
      case 'C': {
        const whole = this.#whole && !(this.#programLast && this.programs.pass === PASS.UNDERRUN);
        return reply({ op: 'C', boot: this.boot, fires: this.#fires, whole });
      }
      case 'Q': return reply({ op: 'Q', free: this.programs.free, armed: this.programs.armed, pass: this.programs.pass });
      case 'W': return reply({ op: 'W', us: Math.floor(this.clock.now) >>> 0 }); // one clock with the Mega's here
      case 'G': this.#start(); return null;
      case 'R':
        if (this.lit || this.programs.running) this.#whole = false; // an exposure cut short
        this.allOff();
        this.programs.discard(PASS.CUT_BY_RESET);
        return null;
      case 'D': this.probe = this.alarmOnDeploy ? 'alarm' : 'deployed'; return null;
      case 'U': if (this.probe !== 'alarm') this.probe = 'stowed'; return null;
      case 'X': this.probe = 'stowed'; this.alarmOnDeploy = false; return null;
      case 'F': this.#fire(cmd.mask, cmd.durations); return null;
    }
  }

  /** The probe pin touched the bed: latch the trigger, as the pin-change interrupt does. */
  trigger(): void {
    this.#latchedTrigger = true;
  }

  deciC(): number[] {
    this.#integrate();
    return this.temp.map((t) => Math.round(t * 10));
  }

  allOff(): void {
    this.#integrate(); // the on-time up to now counts
    this.lit = 0;
    this.#off.forEach((e) => this.clock.cancel(e));
    this.#off = [null, null, null, null];
    if (this.#chainEvent) this.onChainSwitch?.(0);
    this.clock.cancel(this.#chainEvent);
    this.#chainEvent = null;
  }

  /** While a chain runs, as the firmware's main loop does: cut it once no line came for CHAIN_SILENCE_US. */
  #watchSilence(): void {
    this.clock.at(this.#lastLineUs + CHAIN_SILENCE_US + 1, () => {
      if (!this.programs.running) return;
      if (this.clock.now - this.#lastLineUs <= CHAIN_SILENCE_US) return this.#watchSilence();
      this.#integrate();
      this.allOff();
      this.programs.discard(PASS.CUT_BY_SILENCE);
      this.#whole = false;
    });
  }

  /** G: the armed chain runs from 1000 µs after now, its events on the clock. */
  #start(): void {
    if (this.#active()) this.#latched |= FAULT.REFUSED;
    else if (this.lit || this.programs.running) {
      this.#latched |= FAULT.BUSY;
      if (this.programs.running) return; // Q goes on telling the running chain's state
    } else if (this.programs.startable()) {
      this.programs.start();
      this.#fires++;
      this.#whole = true;
      this.#programLast = true;
      this.#watchSilence();
      return this.#schedule(this.clock.now + PROGRAM_START_LEAD_US);
    }
    this.programs.pass = PASS.REFUSED;
  }

  /** The chain's next event after the one at `atUs` (or time 0); at the chain's end every LED is off. */
  #schedule(atUs: number): void {
    const step = this.programs.next();
    if (typeof step === 'string') {
      this.#integrate();
      this.lit = 0;
      this.#chainEvent = null;
      this.onChainSwitch?.(0);
      return;
    }
    const when = atUs + step.d;
    this.#chainEvent = this.clock.at(when, () => {
      this.#integrate();
      if (!this.programs.running) return; // cut meanwhile (the thermal check above)
      this.lit = step.m;
      this.onChainSwitch?.(step.m);
      this.#schedule(when);
    });
  }

  #active(): number {
    return this.#hot ? FAULT.OVERTEMP : 0;
  }

  #fire(mask: number, durations: number[]): void {
    if (this.#active()) return void (this.#latched |= FAULT.REFUSED);
    if (this.lit || this.programs.running) return void (this.#latched |= FAULT.BUSY);
    let on = 0;
    for (let k = 0; k < 4; k++) {
      if (!((mask >> k) & 1) || durations[k] === 0) continue;
      if (durations[k] > this.o.capUs) return void (this.#latched |= FAULT.CAPPED);
      on |= 1 << k;
    }
    this.#integrate();
    if (!on) return;
    this.lit = on;
    this.#fires++;
    this.#whole = true;
    this.#programLast = false;
    for (let k = 0; k < 4; k++) {
      if (!((on >> k) & 1)) continue;
      this.#off[k] = this.clock.after(durations[k], () => {
        this.#integrate();
        this.lit &= ~(1 << k);
        this.#off[k] = null;
      });
    }
  }

  /** Advances the thermal model to now, and cuts the LEDs on over-temperature like the firmware. */
  #integrate(): void {
    const now = this.clock.now;
    const dtUs = now - this.#lastUs;
    this.#lastUs = now;
    if (dtUs <= 0) return;
    for (let k = 0; k < 4; k++) if ((this.lit >> k) & 1) this.onUs[k] += dtUs;
    this.thermal.advance(dtUs, this.lit);
    for (let i = 0; i < SENSOR_COUNT; i++) {
      const t = this.temp[i] * 10;
      if (t >= this.o.limitDeciC[i]) this.#hot |= 1 << i;
      else if (t < this.o.limitDeciC[i] - this.o.hysteresisDeciC) this.#hot &= ~(1 << i);
    }
    if (this.#hot && (this.lit || this.programs.running)) {
      this.allOff();
      this.programs.discard(PASS.CUT_BY_FAULT);
      this.#whole = false;
      this.#latched |= FAULT.CUTOFF;
    }
  }
}

