// One scan pass on the simulated machine (protocol/planner.md "Scan mode"): from rest at its run-up
// the head accelerates, crosses the windows at the speed with the LEDs switching at the plan's
// times, and brakes to rest at its run-out. Records each LED's on-intervals as switched.

import { passDurationUs, passSwitches } from '../planner/job-plan';
import type { ScanPlan } from '../planner/scan';
import type { Clock } from './clock';
import type { NanoModel } from './nano-model';

export interface ScanExposure {
  pass: number;
  hy: number;
  descending: boolean;
  /** Per LED 0-3: [on, off] µs after the pass's start mark, as the printhead switched them. */
  leds: [number, number][][];
}

export interface ScanPassHooks {
  /** The head's move across, from run-up to run-out, taking `us`. */
  moveUs(us: number): void;
  /** The printhead would not light (too hot): the pass is cut. */
  refused(): void;
  done(exposure: ScanExposure): void;
}

export class ScanPassRun {
  #events: object[] = [];
  readonly #exposure: ScanExposure;
  #mask = 0;

  constructor(private readonly clock: Clock, private readonly nano: NanoModel, scan: ScanPlan, index: number, hooks: ScanPassHooks) {
    const pass = scan.passes[index];
    this.#exposure = { pass: index, hy: pass.hy, descending: pass.descending, leds: [[], [], [], []] };
    const start = clock.now;
    const mark = start + scan.accelUs;
    nano.beginScanPass();
    hooks.moveUs(passDurationUs(scan, pass));
    for (const { atUs, mask } of passSwitches(pass)) {
      this.#events.push(clock.at(mark + atUs, () => {
        if (!this.#switch(mask, atUs)) hooks.refused();
      }));
    }
    this.#events.push(clock.at(start + passDurationUs(scan, pass), () => {
      this.#events = [];
      this.#switch(0, this.clock.now - mark);
      nano.endScanPass();
      hooks.done(this.#exposure);
    }));
  }

  /** Cancels what is left of the pass; the caller puts the LEDs out and stops the head. */
  cancel(): void {
    this.#events.forEach((e) => this.clock.cancel(e));
    this.#events = [];
  }

  #switch(mask: number, atUs: number): boolean {
    const ok = this.nano.scanSwitch(mask);
    const now = ok ? mask : 0;
    for (let k = 0; k < 4; k++) {
      const was = (this.#mask >> k) & 1, is = (now >> k) & 1;
      if (!was && is) this.#exposure.leds[k].push([atUs, atUs]);
      if (was && !is) this.#exposure.leds[k][this.#exposure.leds[k].length - 1][1] = atUs;
    }
    this.#mask = now;
    return ok;
  }
}
