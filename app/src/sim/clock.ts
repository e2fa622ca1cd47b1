// Virtual time for the simulated printer: events run in time order as the host advances the clock (µs).

/** What the simulated printer's timers need of time: the firmware module runs between the events, the host's timers and the faults are events. */
export interface Clock {
  readonly now: number;
  at(at: number, run: () => void): object;
  after(us: number, run: () => void): object;
  cancel(e: object | null | undefined): void;
}

interface Event {
  at: number;
  seq: number;
  run: () => void;
}

export class VirtualClock implements Clock {
  now = 0;
  #events: Event[] = [];
  #seq = 0;

  /** Runs `run` at time `at` (µs); returns a handle for cancel(). */
  at(at: number, run: () => void): Event {
    const e = { at: Math.max(at, this.now), seq: this.#seq++, run };
    // Binary insert keeps the queue sorted by (at, seq).
    let lo = 0, hi = this.#events.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      const m = this.#events[mid];
      if (m.at < e.at || (m.at === e.at && m.seq < e.seq)) lo = mid + 1;
      else hi = mid;
    }
    this.#events.splice(lo, 0, e);
    return e;
  }

  after(us: number, run: () => void): Event {
    return this.at(this.now + us, run);
  }

  cancel(e: object | null | undefined): void {
    if (!e) return;
    const i = this.#events.indexOf(e as Event);
    if (i >= 0) this.#events.splice(i, 1);
  }

  /** Runs every event due up to `t`, then sets the time to `t`. */
  advanceTo(t: number): void {
    while (this.#events.length && this.#events[0].at <= t) {
      const e = this.#events.shift()!;
      this.now = e.at;
      e.run();
    }
    this.now = Math.max(this.now, t);
  }

  /** The time of the next event, or Infinity. */
  get next(): number {
    return this.#events.length ? this.#events[0].at : Infinity;
  }
}

/** A view of a clock whose events stop running once it is closed: a model that resets leaves no timer behind. */
export class ClockScope implements Clock {
  #open = true;
  constructor(private readonly clock: VirtualClock) {}

  get now(): number {
    return this.clock.now;
  }

  at(at: number, run: () => void): object {
    return this.clock.at(at, () => this.#open && run());
  }

  after(us: number, run: () => void): object {
    return this.at(this.clock.now + us, run);
  }

  cancel(e: object | null | undefined): void {
    this.clock.cancel(e);
  }

  close(): void {
    this.#open = false;
  }
}
