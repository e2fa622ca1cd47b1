import { describe, expect, it } from 'vitest';
import { GEOMETRIES, planCase, randomJob } from '../planner/golden';
import { encodeJob } from '../protocol/job-encode';
import { SimWire } from '../sim/wire';
import { CommandError } from './dialect-client';
import { DialectLink } from './dialect-link';
import type { LinkFaults } from '../sim/link-faults';
import { CONFIG_DEFAULTS, motionOf } from '../sim/config';

function rig(link: LinkFaults = {}, noSd = false) {
  const wire = new SimWire({ link, noSd });
  const dl = new DialectLink(wire.host, wire.clientOptions);
  const lines: string[] = [];
  let closed: Error | undefined;
  const opened = dl.open((_r, line) => lines.push(line), (e) => (closed = e ?? new Error('closed')));
  return { wire, dl, lines, opened, closed: () => closed };
}

/** Runs virtual time until the promise settles. */
async function settle<T>(wire: SimWire, p: Promise<T>, maxMs = 180_000): Promise<T> {
  let done = false;
  p.then(() => (done = true), () => (done = true));
  for (let t = 0; t < maxMs && !done; t += 5) {
    wire.runUntil(() => done, 5);
    for (let i = 0; i < 10; i++) await Promise.resolve(); // let the client's awaits run between steps
  }
  return p;
}

function job(seed: number) {
  const j = randomJob(seed, GEOMETRIES.adjacent, 'serpentine', [60, 24], 0.5);
  j.dose = { map: 'linear', fullUs: 3000 };
  return j;
}

describe('dialect client over a simulated 115200-baud wire', () => {
  it('learns the window from M115 and matches replies to commands', async () => {
    const r = rig();
    await settle(r.wire, r.opened);
    const temps = await settle(r.wire, r.dl.command('M105'));
    expect(temps[0].kind).toBe('temps');
    await expect(settle(r.wire, r.dl.command('G0 X1'))).rejects.toEqual(new CommandError(14, 'axis not homed: X'));
    await settle(r.wire, r.dl.command('G28'));
    const [pos] = await settle(r.wire, r.dl.command('M114'));
    if (pos.kind !== 'position') console.log(r.lines.slice(-30));
    expect(pos).toMatchObject({ kind: 'position', um: [0, 0, 0] });
    expect(r.lines).toContain('Cap:RX_WINDOW:3');
  });

  it('uploads a job bit-exact through 1 % byte corruption with drops', async () => {
    const r = rig({ corruptPercent: 1, dropPercent: 0.3, seed: 99 });
    await settle(r.wire, r.opened);
    await settle(r.wire, r.dl.command('G28'));
    const j = job(21);
    const progress: number[] = [];
    await settle(r.wire, r.dl.startJob(j, (p) => progress.push(p.bytesVerified)));
    const stored = r.wire.printer.module.card().map(([, text]) => text);
    expect(stored).toContain(encodeJob(j));
    expect(r.dl.health.resends + r.dl.health.timeouts).toBeGreaterThan(0);
    expect(r.dl.health.bytesRetransmitted).toBeGreaterThan(0);
    expect(progress.at(-1)).toBe(encodeJob(j).length);
    expect(r.wire.printer.module.cardJob()).not.toBeNull(); // running
  });

  it('rejects what is pending when the link drops', async () => {
    const r = rig({ disconnectAfterMs: 1500 });
    await settle(r.wire, r.opened);
    const pending = r.dl.command('G4 S10');
    await expect(settle(r.wire, pending)).rejects.toThrow('device lost');
    expect(r.closed()?.message).toBe('device lost');
  });

  it('keeps the Mega busy through its window: a 20 kB upload needs no resend on a clean wire', async () => {
    const r = rig();
    await settle(r.wire, r.opened);
    await settle(r.wire, r.dl.command('G28'));
    const j = job(7);
    const text = encodeJob(j);
    const start = r.wire.printer.clock.now;
    await settle(r.wire, r.dl.startJob({ ...j, gridData: j.gridData }, () => {}));
    const seconds = (r.wire.printer.clock.now - start) / 1e6;
    expect(r.dl.health.resends).toBe(0);
    expect(text.length / seconds).toBeGreaterThan(0.8 * 11520 * (text.length / r.wire.carried.toPrinter));
  });

  it('streams with M828 on a Mega without SD, held back by its buffer, with no time-out and every stop once', async () => {
    const r = rig({}, true);
    await settle(r.wire, r.opened);
    await settle(r.wire, r.dl.command('G28'));
    const j = randomJob(12, GEOMETRIES.adjacent, 'serpentine', [60, 40], 0.9); // what the Mega's stream window takes (a bigger one is E28)
    j.dose = { map: 'linear', fullUs: 3000 };
    const printer = r.wire.printer;
    const { stops } = planCase('', j, motionOf(CONFIG_DEFAULTS, [0, 0])).plan;
    await settle(r.wire, r.dl.startJob(j, () => {}), 600_000);
    expect(r.lines).toContain('echo:Streaming: exposed as it arrives, no resume');
    expect(r.lines.filter((l) => l.startsWith('busy:')).length).toBeGreaterThan(0); // it was held back
    expect(r.dl.health.timeouts).toBe(0);
    expect(r.dl.health.resends).toBe(0);
    r.wire.runUntil(() => r.lines.some((l) => l.startsWith('JOB:done')), 600_000);
    expect(r.lines.find((l) => l.startsWith('JOB:done'))).toContain(`stop=${stops.length}/${stops.length}`);
    expect(printer.module.fires).toBe(stops.filter((s) => s.slice(2).some((us) => us > 0)).length);
  });
});
