// The simulated Mega's axes: queued trapezoidal moves in virtual time, homing, jogging and soft limits.

import { moveTimeUs } from '../planner/time-model';
import type { Clock } from './clock';
import { num, topSpeedUmS } from './config';

export type Xyz = [number, number, number];

interface Move {
  to: Xyz;
  /** mm/s along each axis, capped per axis. */
  feed: number;
  /** A move whose time the caller knows (a scan pass at its speed), µs. */
  us?: number;
}

export const MOVE_QUEUE = 8;

export class Motion {
  /** Position at the end of the last finished move, µm. */
  pos: Xyz = [0, 0, 0];
  homed: [boolean, boolean, boolean] = [false, false, false];
  enabled = false;
  #queue: Move[] = [];
  #current: { from: Xyz; to: Xyz; start: number; end: number } | null = null;
  #timer: object | null = null;
  #idle: (() => void)[] = [];

  constructor(private readonly clock: Clock, private readonly config: Record<string, string>) {}

  get movesFree(): number {
    return MOVE_QUEUE - this.#queue.length - (this.#current ? 1 : 0);
  }

  get moving(): boolean {
    return this.#current !== null;
  }

  /** Where the head is now, µm, interpolated along the current move. */
  now(): Xyz {
    const c = this.#current;
    if (!c) return [...this.pos];
    const f = c.end > c.start ? Math.min(1, (this.clock.now - c.start) / (c.end - c.start)) : 1;
    return [0, 1, 2].map((i) => Math.round(c.from[i] + (c.to[i] - c.from[i]) * f)) as Xyz;
  }

  /** Axis limits in µm. */
  max(axis: number): number {
    return num(this.config, ['bed.x', 'bed.y', 'bed.z'][axis]) * 1000;
  }

  /** Time in µs for a move from `from` to `to` at up to `feed` mm/s: the slowest axis. */
  duration(from: Xyz, to: Xyz, feed: number): number {
    let t = 0;
    for (let i = 0; i < 3; i++) {
      const v = Math.min(Math.round(feed * 1000), topSpeedUmS(this.config, i));
      const a = num(this.config, ['accel.x', 'accel.y', 'accel.z'][i]) * 1000;
      t = Math.max(t, moveTimeUs(Math.abs(to[i] - from[i]), v, a));
    }
    return t;
  }

  enqueue(to: Xyz, feed: number): void {
    this.enabled = true;
    this.#queue.push({ to, feed });
    if (!this.#current) this.#startNext();
  }

  /** A move that takes `us` µs, as a scan pass from its run-up to its run-out does. */
  enqueueTimed(to: Xyz, us: number): void {
    this.enabled = true;
    this.#queue.push({ to, feed: 0, us });
    if (!this.#current) this.#startNext();
  }

  /** Calls `fn` once the queue is empty and the axes stand still. */
  whenIdle(fn: () => void): void {
    if (!this.#current) fn();
    else this.#idle.push(fn);
  }

  /** Stops at once where the head is: M410, M112, a jog's end. */
  stop(): void {
    this.pos = this.now();
    this.#queue = [];
    this.#current = null;
    this.clock.cancel(this.#timer);
    this.#flushIdle();
  }

  release(): void {
    this.stop();
    this.enabled = false;
    this.homed = [false, false, false];
  }

  #startNext(): void {
    const m = this.#queue.shift();
    if (!m) {
      this.#current = null;
      this.#flushIdle();
      return;
    }
    const from = [...this.pos] as Xyz;
    const start = this.clock.now;
    const end = start + (m.us ?? this.duration(from, m.to, m.feed));
    this.#current = { from, to: m.to, start, end };
    this.#timer = this.clock.at(end, () => {
      this.pos = m.to;
      this.#startNext();
    });
  }

  #flushIdle(): void {
    const fns = this.#idle;
    this.#idle = [];
    fns.forEach((f) => f());
  }
}
