// A page reload with the simulated printer: what the browser kept starts the same machine, which ran
// its job on while no page was there (the firmware's own resume, as a machine with no host would
// carry on), and a reconnect that offers the resume (issue 17, item 5).
import { describe, expect, it } from 'vitest';
import { encodeJob } from '../protocol/job-encode';
import { SimHost } from './sim-host.fixture';
import { SimKeeper } from './sim-keeper';
import { FakeStore, smallJob } from './sim-store.fixture';

/** The stops done, by the checkpoint the firmware reports after a reset. */
const interrupted = (h: SimHost) => /^JOB:interrupted file=R\.UVJ stop=(\d+)\/(\d+)$/.exec(h.cmd('M1000 S')[0]);

/** A page running a job at `speed`, kept as the worker keeps it; returns the host and the store once `fires` exposures are done. */
async function pageWithJob(fires: number, speed: number, clock: { wall: number }) {
  const h = new SimHost();
  const store = new FakeStore();
  const keeper = new SimKeeper(h.sim, store.write, () => speed, undefined, () => clock.wall);
  h.cmd('G28');
  const job = smallJob(9);
  job.dose = { map: 'linear', fullUs: 200_000 }; // some 10 s of exposing: still under way when the page comes back
  h.upload('R.UVJ', encodeJob(job));
  h.cmd('M23 R.UVJ');
  h.cmd('M24');
  while (h.sim.module.fires < fires) {
    h.sim.advance(1);
    clock.wall += 1 / speed;
    await keeper.keep(); // the worker keeps after every tick
  }
  return { h, store };
}

describe('simulated printer: a page reload', () => {
  it('finds the job run on while the page was away, offers it, and resumes it to its end', async () => {
    const clock = { wall: 1_000_000 };
    const { store } = await pageWithJob(20, 2, clock);
    const { saved, running, note } = store.kept(); // the page goes, and its worker with it
    expect(note).toBeNull();
    expect(running).toEqual({ atMs: expect.any(Number), speed: 2, paced: false });
    const kept = new SimHost({ saved }, false); // what the checkpoint alone says
    kept.boot();
    const atCheckpoint = Number(interrupted(kept)?.[1]);

    clock.wall += 3000; // 3 s away at 2x: 6 s of the printer's time, homing included
    const next = new SimHost({ saved }, false);
    next.sim.runOn((clock.wall - running!.atMs) * running!.speed, running!.paced);
    expect(next.lines).toEqual([]); // nobody listened
    expect(next.sim.module.fires).toBeGreaterThan(0); // it exposed on
    next.boot(); // the new page opens the link: the Mega resets, the printhead runs on
    const offer = interrupted(next);
    expect(Number(offer?.[1])).toBeGreaterThan(atCheckpoint);
    next.cmd('G28');
    const from = next.lines.length;
    next.cmd('M1000');
    expect(next.waitFor(/^JOB:done/)).toContain(`stop=${offer?.[2]}/${offer?.[2]}`);
    expect(next.lines.slice(from).find((l) => l.startsWith('echo:resume:'))).toMatch(/^echo:resume: stop \d+/);
    expect(next.cmd('M1000 S')[0]).toBe('JOB:idle');
  });

  it('runs a job on to its end when the page was away long enough: nothing is offered', async () => {
    const clock = { wall: 0 };
    const { store } = await pageWithJob(5, 1, clock);
    const { saved, running } = store.kept();
    const next = new SimHost({ saved }, false);
    next.sim.runOn(3_600_000, running!.paced);
    expect(next.sim.module.cardJob()).toBeNull();
    next.boot();
    expect(next.cmd('M1000 S')[0]).toBe('JOB:idle');
  });

  it('offers a paused job where it paused, without running it on', async () => {
    const clock = { wall: 0 };
    const { h, store } = await pageWithJob(5, 1, clock);
    h.cmd('M25');
    h.waitFor(/^JOB:paused/);
    const paused = Number(/stop=(\d+)\//.exec(h.cmd('M27').find((l) => l.startsWith('JOB:'))!)?.[1]);
    const keeper = new SimKeeper(h.sim, store.write, () => 1);
    await keeper.keep();
    const { saved, running } = store.kept();
    expect(running).toBeNull();
    const next = new SimHost({ saved });
    expect(Number(interrupted(next)?.[1])).toBe(paused);
  });

  it('keeps the settings saved with M500 and the start count, not the settings left unsaved', async () => {
    const h = new SimHost();
    const store = new FakeStore();
    const keeper = new SimKeeper(h.sim, store.write, () => 1);
    h.cmd('M850 speed.travel 120');
    h.cmd('M500');
    h.cmd('M850 accel.x 2500'); // not saved
    h.sim.powerCycle();
    await keeper.keep();
    const next = new SimHost({ saved: store.kept().saved });
    expect(next.cmd('M850 speed.travel')[0]).toBe('M850 speed.travel 120');
    expect(next.cmd('M850 accel.x')[0]).toBe('M850 accel.x 2000');
    expect(next.sim.boots).toBe(3); // a third power-up of the same machine
  });
});
