// A page reload with the simulated printer: what the browser kept starts the same machine, which ran
// its job on while no page was there, and a reconnect that offers the resume (issue 17, item 5).
import { describe, expect, it } from 'vitest';
import { encodeJob } from '../protocol/job-encode';
import { SimHost } from './sim-host.fixture';
import { SimKeeper } from './sim-keeper';
import { FakeStore, smallJob } from './sim-store.fixture';

const range = (n: number) => Array.from({ length: n }, (_, i) => i);

/** A page running a job at `speed`, kept as the worker keeps it; returns the host and the store once `stops` are done. */
async function pageWithJob(stops: number, speed: number, clock: { wall: number }) {
  const h = new SimHost();
  const store = new FakeStore();
  const keeper = new SimKeeper(h.sim, store.write, () => speed, undefined, () => clock.wall);
  h.cmd('G28');
  h.upload('R.UVJ', encodeJob(smallJob(9)));
  h.cmd('M23 R.UVJ');
  h.cmd('M24');
  while (h.sim.mega.job.exposures.length < stops) {
    h.sim.advance(1);
    clock.wall += 1 / speed;
    await keeper.keep(); // the worker keeps after every tick
  }
  return { h, store, total: h.sim.mega.job.plan!.count };
}

describe('simulated printer: a page reload', () => {
  it('finds the job run on while the page was away, offers it, and resumes it with every stop exactly once', async () => {
    const clock = { wall: 1_000_000 };
    const { h, store, total } = await pageWithJob(20, 2, clock);
    const { saved, running, note } = store.kept(); // the page goes, and its worker with it
    expect(note).toBeNull();
    const cp = saved!.checkpoint!;
    expect(running).not.toBeNull();
    // What happened after the last write went with the page: the kept checkpoint is the truth.
    const before = h.sim.mega.job.exposures.map((e) => e.stop).filter((s) => s < cp.done);

    clock.wall += 150; // 150 ms away at 2x: 300 ms of the printer's time
    const next = new SimHost({ saved }, false);
    next.sim.runOn(running!.pos, (clock.wall - running!.atMs) * running!.speed);
    expect(next.lines).toEqual([]); // nobody listened
    const ranOn = next.sim.mega.job.exposures.map((e) => e.stop);
    expect(ranOn[0]).toBe(cp.done);
    expect(ranOn.length).toBeGreaterThan(10);
    expect(next.sim.clock.now).toBeGreaterThanOrEqual(300_000 - 2000); // the time of the checkpoint's write is kept to the tick
    next.sim.resetMega(); // the new page opens the link: the Mega resets, the printhead runs on
    expect(next.lines).toEqual(['start']);
    const offer = next.cmd('M1000 S')[0];
    expect(offer).toBe(`JOB:interrupted file=R.UVJ stop=${cp.done + ranOn.length}/${total}`);
    next.cmd('G28');
    expect(next.cmd('M1000').join('\n')).toMatch(/echo:resume: stop \d+ (had not been sent|was cut short, and is exposed again)/); // the same start of the printhead
    next.waitFor(/^JOB:done/);
    const after = next.sim.mega.job.exposures.map((e) => e.stop);
    expect([...before, ...ranOn, ...after]).toEqual(range(total));
    expect(next.cmd('M1000 S')[0]).toBe('JOB:idle');
  });

  it('runs a job on to its end when the page was away long enough: nothing is offered', async () => {
    const clock = { wall: 0 };
    const { store, total } = await pageWithJob(5, 1, clock);
    const { saved, running } = store.kept();
    const next = new SimHost({ saved }, false);
    next.sim.runOn(running!.pos, 3_600_000);
    expect(next.sim.mega.job.state).toBe('done');
    expect(next.sim.mega.job.exposures.at(-1)?.stop).toBe(total - 1);
    next.sim.resetMega();
    expect(next.cmd('M1000 S')[0]).toBe('JOB:idle');
  });

  it('offers a paused job where it paused, without running it on', async () => {
    const clock = { wall: 0 };
    const { h, store } = await pageWithJob(5, 1, clock);
    h.cmd('M25');
    h.waitFor(/^JOB:paused/);
    const keeper = new SimKeeper(h.sim, store.write, () => 1);
    await keeper.keep();
    const { saved, running } = store.kept();
    expect(running).toBeNull();
    const next = new SimHost({ saved });
    expect(next.cmd('M1000 S')[0]).toBe(`JOB:interrupted file=R.UVJ stop=${h.sim.sd.checkpoint!.done}/${h.sim.mega.job.plan!.count}`);
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
    expect(next.sim.nano.boot).toBe(3); // a third power-up of the same machine
  });
});
