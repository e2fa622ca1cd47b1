// The simulated Mega's motion commands (protocol/mega.md §5 "Motion"): moves at a modal feed rate, dwell,
// waiting for the queue, homing, releasing the motors, jogging and the kinematic self-test.

import type { Command } from '../protocol/dialect-command';
import { num } from './config';
import type { Handler, MegaModel } from './mega';
import type { Xyz } from './motion';

const AXES = ['X', 'Y', 'Z'] as const;
const params = (c: Command) => ('params' in c ? c.params : {});
/** Where the last queued move ends, so relative moves add up while earlier ones still run. */
const lastTarget = new WeakMap<MegaModel, Xyz>();

function queuedTarget(m: MegaModel): Xyz {
  const t = lastTarget.get(m);
  return m.motion.moving && t ? [...t] : m.motion.now();
}

function move(m: MegaModel, c: Command, done: () => void): void {
  const p = params(c);
  const target = [...m.motion.now()] as Xyz;
  const base = queuedTarget(m);
  for (const [i, a] of AXES.entries()) {
    const v = p[a];
    if (v === undefined) continue;
    if (v === null) return m.error(11, done);
    if (!m.motion.homed[i]) return m.error(14, done, a);
    target[i] = m.absolute ? v : base[i] + v;
  }
  for (const [i, a] of AXES.entries()) {
    if (p[a] === undefined) target[i] = base[i];
    if (target[i] < 0 || target[i] > m.motion.max(i)) return m.error(15, done, a);
  }
  if (typeof p.F === 'number' && p.F <= 0) return m.error(11, done, 'F');
  // Kept only once the move is accepted: a refused line leaves the machine as it was.
  if (typeof p.F === 'number') m.feedMmS = Math.max(1, Math.floor(p.F / 60)) / 1000; // whole µm/s, as the Mega's
  const feed = m.feedMmS ?? num(m.config, 'speed.travel');
  const go = () => {
    m.motion.enqueue(target, feed);
    lastTarget.set(m, target);
    done();
  };
  if (m.motion.movesFree > 0) go();
  else m.motion.whenIdle(go); // queue full: the line waits, as on the Mega
}

/** G28: queued moves finish first (as in Marlin), then each named axis seeks its switch. */
function home(m: MegaModel, c: Command, done: () => void): void {
  const p = params(c);
  const all = !('X' in p) && !('Y' in p) && !('Z' in p);
  const axes = [0, 1, 2].filter((i) => all || AXES[i] in p);
  m.long(done, (finish) => {
    m.motion.whenIdle(() => {
      const from = m.motion.now();
      const to = [...from] as Xyz;
      for (const i of axes) to[i] = 0;
      // Unknown positions home from as far as the axis reaches; the back-off adds 2 × 2 mm slowly.
      const start = from.map((v, i) => (m.motion.homed[i] ? v : m.motion.max(i))) as Xyz;
      const t = m.motion.duration(start, to, num(m.config, 'speed.home')) + 2 * m.motion.duration([0, 0, 0], [2000, 2000, 2000], 5);
      m.clock.after(t, () => {
        m.motion.pos = to;
        for (const i of axes) m.motion.homed[i] = true;
        m.motion.enabled = true;
        finish();
      });
    });
  });
}

/** G4: the moves before it finish, then the dwell runs (Marlin plans G4 as a wait after the queue). */
function dwell(m: MegaModel, c: Command, done: () => void): void {
  const p = params(c);
  const us = typeof p.P === 'number' ? p.P : typeof p.S === 'number' ? p.S * 1000 : 0; // P ms, S s, both in thousandths
  if (us > 4_294_967_000) return m.error(11, done, 'S'); // mega.md: at most 4294967 ms
  m.long(done, (finish) => m.motion.whenIdle(() => m.clock.after(us, finish)));
}

/** M18/M84: the queued moves end first, as Marlin's, so the head stops where they were sent; then the motors let go. */
function release(m: MegaModel, done: () => void): void {
  m.long(done, (finish) => m.motion.whenIdle(() => (m.motion.release(), finish())));
}

function jog(m: MegaModel, c: Command, done: () => void): void {
  const p = params(c);
  const axis = AXES.findIndex((a) => typeof p[a] === 'number');
  if (axis < 0 || Math.abs(p[AXES[axis]]!) !== 1000) return m.error(11, done);
  if (!m.motion.homed[axis]) return m.error(14, done, AXES[axis]);
  const dir = p[AXES[axis]]! > 0 ? 1 : -1;
  const speed = num(m.config, p.S === 1000 ? 'speed.jog_fast' : 'speed.jog_slow');
  m.motion.stop();
  const to = m.motion.now();
  to[axis] = dir > 0 ? m.motion.max(axis) : 0;
  m.motion.enqueue(to, speed);
  done();
}

function selfTest(m: MegaModel, mode: 'quick' | 'full', done: () => void): void {
  if (!m.motion.homed[0] || !m.motion.homed[1]) return m.error(14, done, 'home first (G28)');
  m.long(done, (finish) => {
    const reach = mode === 'full' ? [m.motion.max(0), m.motion.max(1)] : [20000, 20000];
    const there: Xyz = [reach[0], reach[1], m.motion.pos[2]];
    m.motion.enqueue(there, num(m.config, 'speed.travel'));
    m.motion.enqueue([0, 0, m.motion.pos[2]], num(m.config, 'speed.home'));
    m.motion.whenIdle(() => {
      const steps = (i: number) => Math.round((reach[i] / 1000) * num(m.config, i ? 'steps_per_mm.y' : 'steps_per_mm.x'));
      m.line(`TEST:${mode} x=pass x_steps=${steps(0)} y=pass y_steps=${steps(1)}`);
      finish();
    });
  });
}

export function motionCommands(m: MegaModel): Record<string, Handler> {
  return {
    G0: (c, done) => move(m, c, done),
    G1: (c, done) => move(m, c, done),
    G4: (c, done) => dwell(m, c, done),
    G28: (c, done) => home(m, c, done),
    G90: (_c, done) => ((m.absolute = true), done()),
    G91: (_c, done) => ((m.absolute = false), done()),
    M400: (_c, done) => m.long(done, (finish) => m.motion.whenIdle(finish)),
    M17: (_c, done) => ((m.motion.enabled = true), done()),
    M18: (_c, done) => release(m, done),
    M84: (_c, done) => release(m, done),
    M410: (_c, done) => (m.motion.stop(), done()),
    // Marlin's "stop waiting for heaters": nothing here heats, so there is never a wait to break.
    M108: (_c, done) => done(),
    M820: (c, done) => jog(m, c, done),
    M822: (c, done) => selfTest(m, 'Q' in params(c) ? 'quick' : 'full', done),
    M119: (_c, done) => {
      const pos = m.motion.now();
      const at = (i: number) => (m.motion.homed[i] && pos[i] === 0 ? 'TRIGGERED' : 'open');
      m.line(`x_min: ${at(0)}`);
      m.line(`y_min: ${at(1)}`);
      m.line(`z_min: ${at(2)}`);
      m.line(`z_probe: ${m.nano.touching ? 'TRIGGERED' : 'open'}`);
      done();
    },
  };
}
