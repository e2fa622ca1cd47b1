// The simulated Mega's printhead and probe commands (protocol/mega.md §5 "Printhead and probe"): the probe
// servo, single probes over the simulated bed, the mesh and leveling, the work light.

import { formatMilli, type Command } from '../protocol/dialect-command';
import { formatReply } from '../protocol/dialect-reply';
import { bedZ } from './bed';
import { num } from './config';
import type { Handler, MegaModel } from './mega';
import type { Xyz } from './motion';

const params = (c: Command) => ('params' in c ? c.params : {});

function probeServo(m: MegaModel, op: 'D' | 'U' | 'X', done: () => void): void {
  if (!m.nano.present) return m.error(30, done);
  m.nanoSay(op);
  m.clock.after(300_000, () => {
    if (m.nano.probe === 'alarm') {
      m.line('PROBE:alarm');
      return m.error(40, done);
    }
    m.line(op === 'D' ? 'PROBE:deployed' : 'PROBE:stowed');
    done();
  });
}

/** Lowers Z until the pin touches the bed at the current X/Y; reports `Bed X: Y: Z:`. */
function probeHere(m: MegaModel, done: () => void, then: (zUm: number) => void): void {
  if (!m.motion.homed[2] || !m.motion.homed[0] || !m.motion.homed[1]) return m.error(14, done, 'home first (G28)');
  if (m.nano.probe !== 'deployed') return m.error(m.nano.probe === 'alarm' ? 40 : 41, done, 'deploy the probe (M401)');
  m.motion.whenIdle(() => {
    const at = m.motion.now();
    const surface = bedZ(m.o.bed, at[0], at[1]);
    const dz = Math.abs(at[2] - surface) + 2000;
    const t = m.motion.duration([0, 0, 0], [0, 0, dz], 4);
    m.clock.after(t, () => {
      m.nano.touching = true;
      m.nano.trigger();
      m.motion.pos = [at[0], at[1], surface];
      const lift: Xyz = [at[0], at[1], surface + 5000];
      m.line(formatReply({ kind: 'probePoint', um: [at[0], at[1], surface] }));
      m.nano.touching = false;
      m.motion.enqueue(lift, num(m.config, 'speed.z'));
      m.motion.whenIdle(() => then(surface));
    });
  });
}

function meshLines(m: MegaModel): string[] {
  const g = m.mesh!;
  return [
    `MESH:grid ${g.nx} ${g.ny} x0=${formatMilli(g.x0)} y0=${formatMilli(g.y0)} dx=${formatMilli(g.dx)} dy=${formatMilli(g.dy)}`,
    ...g.z.map((row, j) => `MESH:row ${j} ${row.map(formatMilli).join(' ')}`),
  ];
}

function level(m: MegaModel, c: Command, done: () => void): void {
  const p = params(c);
  const nx = typeof p.X === 'number' ? p.X / 1000 : num(m.config, 'mesh.nx');
  const ny = typeof p.Y === 'number' ? p.Y / 1000 : num(m.config, 'mesh.ny');
  if (!Number.isInteger(nx) || !Number.isInteger(ny) || nx < 3 || nx > 9 || ny < 3 || ny > 9) return m.error(11, done);
  const margin = num(m.config, 'mesh.margin') * 1000;
  const x0 = margin, y0 = margin;
  const dx = Math.floor((m.motion.max(0) - 2 * margin) / (nx - 1));
  const dy = Math.floor((m.motion.max(1) - 2 * margin) / (ny - 1));
  const z: number[][] = Array.from({ length: ny }, () => new Array<number>(nx).fill(0));
  m.long(done, (finish) => {
    const points: [number, number][] = [];
    for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) points.push([i, j]);
    const nextPoint = (k: number) => {
      if (k === points.length) {
        m.mesh = { nx, ny, x0, y0, dx, dy, z };
        m.leveling = true;
        m.sd.files.set('MESH.TXT', JSON.stringify(m.mesh));
        meshLines(m).forEach((l) => m.line(l));
        return finish();
      }
      const [i, j] = points[k];
      const i2 = j % 2 ? nx - 1 - i : i; // serpentine over the grid
      m.motion.enqueue([x0 + i2 * dx, y0 + j * dy, m.motion.pos[2]], num(m.config, 'speed.travel'));
      probeHere(m, finish, (zUm) => {
        z[j][i2] = zUm;
        nextPoint(k + 1);
      });
    };
    nextPoint(0);
  });
}

export function probeCommands(m: MegaModel): Record<string, Handler> {
  return {
    M401: (_c, done) => probeServo(m, 'D', done),
    M402: (_c, done) => probeServo(m, 'U', done),
    M280: (c, done) => {
      const s = params(c).S;
      const op = s === 10000 ? 'D' : s === 90000 ? 'U' : s === 160000 ? 'X' : null;
      if (params(c).P !== 0 || !op) return m.error(11, done);
      probeServo(m, op, done);
    },
    G30: (_c, done) => probeHere(m, done, () => done()),
    G29: (c, done) => level(m, c, done),
    M420: (c, done) => {
      const p = params(c);
      if ('V' in p) {
        if (!m.mesh) return m.error(11, done, 'no mesh');
        meshLines(m).forEach((l) => m.line(l));
      }
      if (typeof p.S === 'number') {
        if (p.S && !m.mesh) return m.error(11, done, 'no mesh');
        m.leveling = p.S !== 0;
      } else if (!('V' in p)) m.line(`echo:leveling ${m.leveling ? 'on' : 'off'}`);
      done();
    },
    M355: (c, done) => ((m.light = (params(c).S ?? 0) !== 0), done()),
  };
}
