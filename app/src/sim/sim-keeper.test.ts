import { describe, expect, it } from 'vitest';
import { encodeJob } from '../protocol/job-encode';
import { SimHost } from './sim-host.fixture';
import { keepingNote, SimKeeper } from './sim-keeper';
import { FakeStore, smallJob } from './sim-store.fixture';

const CHECKPOINT = 'JOB~CKP'; // the firmware's checkpoint file (job_files.h)

describe('SimKeeper', () => {
  it('keeps the card when a file is written, and writes nothing when nothing changed', async () => {
    const h = new SimHost();
    const store = new FakeStore();
    const keeper = new SimKeeper(h.sim, store.write, () => 1);
    await keeper.keep();
    expect(store.writes).toEqual([['card', 'machine']]);
    expect(keeper.keep()).toBeNull();
    h.upload('K.UVJ', encodeJob(smallJob(1)));
    await keeper.keep();
    expect(store.writes.at(-1)).toEqual(['card']);
    expect(store.kept().saved?.files.map(([name]) => name)).toContain('K.UVJ');
    h.cmd('M30 K.UVJ');
    await keeper.keep();
    expect(store.kept().saved?.files.map(([name]) => name)).not.toContain('K.UVJ');
  });

  it('keeps each checkpoint as the Mega writes it, with the time of a running job', async () => {
    const h = new SimHost();
    const store = new FakeStore();
    let wall = 5000;
    const keeper = new SimKeeper(h.sim, store.write, () => 4, undefined, () => wall);
    h.cmd('G28');
    h.upload('C.UVJ', encodeJob(smallJob(2)));
    h.cmd('M23 C.UVJ');
    h.cmd('M24');
    const seen = new Set<string>();
    while (h.sim.module.fires < 10) {
      h.sim.advance(1);
      wall += 1;
      await keeper.keep();
      const kept = new Map(store.kept().saved?.files).get(CHECKPOINT);
      if (kept) seen.add(kept);
      expect(kept).toBe(new Map(h.sim.module.card()).get(CHECKPOINT)); // the card as it is, after every tick
    }
    expect(seen.size).toBeGreaterThanOrEqual(5); // a write for every checkpoint
    const { running } = store.kept();
    expect(running?.speed).toBe(4);
    expect(running?.atMs).toBeLessThanOrEqual(wall);
    expect(running?.atMs).toBeGreaterThan(wall - 20); // the last checkpoint's time
    h.cmd('M25');
    h.waitFor(/^JOB:paused/);
    await keeper.keep();
    expect(store.kept().running).toBeNull(); // a paused job does not run on
  });

  it('keeps the settings M500 saved, and writes one thing at a time', async () => {
    const h = new SimHost();
    const store = new FakeStore();
    const keeper = new SimKeeper(h.sim, store.write, () => 1);
    await keeper.keep();
    let release = () => {};
    store.hold = new Promise((r) => (release = r));
    h.cmd('M850 speed.travel 120');
    h.cmd('M500');
    const writing = keeper.keep();
    expect(writing).not.toBeNull();
    expect(keeper.keep()).toBeNull(); // under way: the next tick takes what changes meanwhile
    release();
    await writing;
    expect(store.kept().saved?.eeprom).toEqual(h.sim.module.eeprom());
    expect(store.kept().saved?.files.find(([name]) => name === 'CONFIG.TXT')?.[1]).toContain('speed.travel = 120');
  });

  it('says once that a write failed, then writes no more', async () => {
    const h = new SimHost();
    const store = new FakeStore();
    store.fail = true;
    const failures: unknown[] = [];
    const keeper = new SimKeeper(h.sim, store.write, () => 1, (e) => failures.push(e));
    await keeper.keep();
    h.upload('F.UVJ', encodeJob(smallJob(3)));
    expect(keeper.keep()).toBeNull();
    expect(failures).toHaveLength(1);
    expect(keepingNote('failed', null)).toMatch(/could no longer be kept/);
  });

  it('switched off, keeps the checkpoint of a running job but not the job running', async () => {
    const h = new SimHost();
    const store = new FakeStore();
    const keeper = new SimKeeper(h.sim, store.write, () => 1);
    h.cmd('G28');
    h.upload('O.UVJ', encodeJob(smallJob(4)));
    h.cmd('M23 O.UVJ');
    h.cmd('M24');
    while (h.sim.module.fires < 3) h.sim.advance(1);
    await keeper.keep();
    expect(store.kept().running).not.toBeNull();
    await keeper.switchOff();
    expect(store.kept().running).toBeNull();
    expect(new Map(store.kept().saved?.files).get(CHECKPOINT)).toBe(new Map(h.sim.module.card()).get(CHECKPOINT));
  });
});
