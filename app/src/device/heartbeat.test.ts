// The host's heartbeat: the Mega pauses a running job no host has spoken to for 30 s of its time
// (mega.md §6). The app's reports come by themselves, so its link says something every 10 s.
import { describe, expect, it } from 'vitest';
import { GEOMETRIES, randomJob } from '../planner/test-jobs';
import { SimWire } from '../sim/wire';
import { DialectLink, HEARTBEAT_MS } from './dialect-link';
import type { Transport } from './transport';

async function settle<T>(wire: SimWire, p: Promise<T>): Promise<T> {
  let done = false;
  p.then(() => (done = true), () => (done = true));
  while (!done) {
    wire.runUntil(() => done, 5);
    await new Promise((resolve) => setImmediate(resolve));
  }
  return p;
}

describe('the link keeps a long job from pausing for a lost host', () => {
  it('runs a job of minutes to its end with nothing but its reports coming back', { timeout: 120_000 }, async () => {
    const wire = new SimWire();
    const link = new DialectLink(wire.host, wire.clientOptions);
    const lines: string[] = [];
    await settle(wire, link.open((_r, line) => lines.push(line), () => {}));
    await settle(wire, link.command('M27 S1'));
    await settle(wire, link.command('G28'));
    const job = randomJob(4, GEOMETRIES.adjacent, 'serpentine', [30, 20], 0.5);
    job.dose = { map: 'linear', fullUs: 700_000 }; // over a minute of exposing
    await settle(wire, link.startJob(job, () => {}));
    for (let t = 0; t < 400 && !lines.some((l) => /^JOB:(done|paused)/.test(l)); t++) {
      wire.runUntil(() => false, 1000);
      await new Promise((resolve) => setImmediate(resolve));
    }
    const end = lines.find((l) => /^JOB:(done|paused)/.test(l)) ?? '';
    expect(end).toMatch(/^JOB:done/);
    const elapsedS = Number(/elapsed=(\d+)/.exec(end)?.[1]);
    expect(elapsedS).toBeGreaterThan(60); // twice the Mega's 30 s and more, with no line but the heartbeat's
    expect(lines.filter((l) => l.startsWith('T:')).length).toBeGreaterThanOrEqual(Math.floor(elapsedS / 10) - 1); // its answers
  });
});

describe("the heartbeat follows the printer's speed", () => {
  it('beats at the new period from the moment the speed changes (the simulated printer at 20x)', async () => {
    const wire = new SimWire();
    const host: Transport = { ...wire.host, timeScale: 1, onRescaled: null };
    const periods: number[] = [];
    const link = new DialectLink(host, { ...wire.clientOptions, setTimer: (fn, ms) => (periods.push(ms), wire.clientOptions.setTimer!(fn, ms)) });
    await settle(wire, link.open(() => {}, () => {}));
    expect(periods.at(-1)).toBe(HEARTBEAT_MS);
    (host as { timeScale: number }).timeScale = 20;
    host.onRescaled?.();
    expect(periods.at(-1)).toBe(HEARTBEAT_MS / 20);
    await link.close();
    expect(host.onRescaled).toBeNull(); // nobody left to tell
  });
});
