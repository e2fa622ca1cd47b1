import { describe, expect, it } from 'vitest';
import { GEOMETRIES, planCase, randomJob } from '../planner/golden';
import type { StrategyName } from '../protocol/job-types';
import { encodeJob } from '../protocol/job-encode';
import { STREAM_BUFFER_CELLS } from './job-stream';
import { SimHost } from './sim-host.fixture';

function job(geometry: [number, number][], strategy: StrategyName, size: [number, number], density: number, seed = 5) {
  const j = randomJob(seed, geometry, strategy, size, density);
  j.originUm = { x: 20000, y: 30000 };
  j.pitchUm = { x: 50, y: 50 };
  j.dose = { map: 'linear', fullUs: 3000 };
  return j;
}

/** A homed printer without an SD card, and the plan the whole job makes from where the head is. */
function noSdPrinter(j: ReturnType<typeof job>) {
  const h = new SimHost({ noSd: true });
  h.cmd('G28');
  h.cmd('G0 X20 Y30'); // over the job's origin, so exposure can begin while the first rows arrive
  h.sim.advance(2000);
  const { stops } = planCase('', j, h.sim.mega.job.machine(h.sim.mega.motion.now())).plan;
  return { h, stops };
}

/** One record as a one-line-at-a-time host sends it: its ok, then the time its bytes take at 115200 baud. */
function send(h: SimHost, record: string): string[] {
  const reply = h.cmd(record);
  h.sim.advance(Math.ceil((record.length + 16) / 11.52));
  return reply;
}

const exposed = (h: SimHost) => h.sim.mega.job.exposures.map((e) => [e.hx, e.hy, ...e.us]);

describe('stream mode (M828) on a Mega without SD', () => {
  for (const strategy of ['serpentine', 'shortest', 'random'] as StrategyName[]) {
    it(`exposes a ${strategy} job while it arrives, each stop of the whole plan once and in order`, () => {
      const j = job(GEOMETRIES.mixed, strategy, [30, 80], 0.3);
      const { h, stops } = noSdPrinter(j);
      expect(h.cmd('M28 A.UVJ')[0]).toMatch(/^echo:E20/); // no card: stream mode is the way
      expect(h.cmd('M828')[0]).toMatch(/^echo:Streaming: .*no resume/);
      const records = encodeJob(j).trimEnd().split('\n');
      let beforeEnd = 0;
      for (const r of records) {
        if (r.startsWith('end')) beforeEnd = h.sim.mega.job.exposures.length;
        send(h, r);
      }
      expect(beforeEnd).toBeGreaterThan(0); // exposure began before the upload ended
      expect(h.cmd('M29')).toContain('echo:Stream complete.');
      h.waitFor(/^JOB:done/);
      expect(exposed(h)).toEqual(stops);
      expect(h.sim.nano.lit).toBe(0);
      expect(h.cmd('M1000 S')[0]).toBe('JOB:idle'); // no checkpoint: no resume
    });
  }

  it('stops at a bad hash with the LEDs off; what was exposed stays, nothing more is', () => {
    const j = job(GEOMETRIES.adjacent, 'serpentine', [24, 80], 0.4);
    const { h, stops } = noSdPrinter(j);
    h.cmd('M828');
    const records = encodeJob(j).trimEnd().replace(/end [0-9a-f]{8}/, 'end 00000000').split('\n');
    const out = records.flatMap((r) => send(h, r));
    expect(out.some((l) => l.startsWith('echo:E24'))).toBe(true);
    expect(h.cmd('M29')[0]).toMatch(/^echo:E24/);
    const n = h.sim.mega.job.exposures.length;
    expect(n).toBeGreaterThan(0);
    expect(n).toBeLessThan(stops.length);
    expect(exposed(h)).toEqual(stops.slice(0, n));
    h.sim.advance(5000);
    expect(h.sim.mega.job.exposures.length).toBe(n);
    expect(h.sim.nano.lit).toBe(0);
    expect(h.cmd('M27')[0]).toMatch(/^JOB:aborted/);
  });

  it('a malformed record ends the stream with E23 and the LEDs off', () => {
    const j = job(GEOMETRIES.adjacent, 'raster', [24, 30], 0.4);
    const { h } = noSdPrinter(j);
    h.cmd('M828');
    const records = encodeJob(j).trimEnd().split('\n');
    records.splice(records.length - 3, 0, 'r 1 0 zz');
    const out = records.flatMap((r) => send(h, r));
    expect(out.filter((l) => l.startsWith('echo:E23'))).toHaveLength(1);
    expect(h.cmd('M29')[0]).toMatch(/^echo:E23/);
    expect(h.sim.nano.lit).toBe(0);
    expect(h.cmd('M27')[0]).toMatch(/^JOB:aborted/);
  });

  it('holds back the host when its buffer is full, and never holds more than the bound', () => {
    const j = job(GEOMETRIES.adjacent, 'serpentine', [200, 100], 0.9);
    const { h, stops } = noSdPrinter(j);
    h.cmd('M828');
    let most = 0;
    let heldBack = 0;
    for (const r of encodeJob(j).trimEnd().split('\n')) {
      const t = h.sim.clock.now;
      send(h, r);
      if (h.sim.clock.now - t > 20_000) heldBack++; // a 70-byte line takes about 7 ms at 115200 baud
      most = Math.max(most, h.sim.mega.streamHeldCells);
    }
    h.cmd('M29');
    h.waitFor(/^JOB:done/);
    expect(exposed(h)).toEqual(stops);
    expect(heldBack).toBeGreaterThan(10);
    expect(most).toBeLessThanOrEqual(STREAM_BUFFER_CELLS + 32); // one record may wait in the line buffer
  });

  it('fails with E28 when the rows the next stops need cannot fit, exposing nothing wrong', () => {
    const far: [number, number][] = [[0, 0], [0, 40], [0, 80], [0, 120]];
    const j = job(far, 'raster', [120, 160], 0.9);
    const { h, stops } = noSdPrinter(j);
    h.cmd('M828');
    const out = encodeJob(j).trimEnd().split('\n').flatMap((r) => send(h, r));
    expect(out.filter((l) => l.startsWith('Error:E28'))).toHaveLength(1);
    expect(h.cmd('M29')[0]).toMatch(/^Error:E28/);
    expect(exposed(h)).toEqual(stops.slice(0, h.sim.mega.job.exposures.length));
    expect(h.sim.nano.lit).toBe(0);
  });

  it('pauses and continues between records', () => {
    const j = job(GEOMETRIES.adjacent, 'serpentine', [24, 30], 0.4);
    const { h, stops } = noSdPrinter(j);
    h.cmd('M828');
    const records = encodeJob(j).trimEnd().split('\n');
    const half = Math.floor(records.length / 2);
    records.slice(0, half).forEach((r) => send(h, r));
    h.cmd('M25');
    h.waitFor(/^JOB:paused/);
    const n = h.sim.mega.job.exposures.length;
    records.slice(half).forEach((r) => send(h, r));
    h.cmd('M29');
    h.sim.advance(3000);
    expect(h.sim.mega.job.exposures.length).toBe(n);
    h.cmd('M24');
    h.waitFor(/^JOB:done/);
    expect(exposed(h)).toEqual(stops);
  });

  it('after an abort drops the rest of its records, and the next command ends it', () => {
    const j = job(GEOMETRIES.adjacent, 'serpentine', [24, 80], 0.4);
    const { h } = noSdPrinter(j);
    h.cmd('M828');
    const records = encodeJob(j).trimEnd().split('\n');
    const half = Math.floor(records.length / 2);
    records.slice(0, half).forEach((r) => send(h, r));
    h.cmd('M524'); // obeyed between records
    expect(h.sim.nano.lit).toBe(0);
    const n = h.sim.mega.job.exposures.length;
    const rest = records.slice(half, half + 5).flatMap((r) => send(h, r));
    expect(rest.every((l) => l.startsWith('ok'))).toBe(true); // read and dropped, no error storm
    expect(h.sim.mega.job.exposures.length).toBe(n);
    expect(h.cmd('M114')[0]).toMatch(/^X:/); // a host that moved on without M29 gets its commands obeyed
    expect(h.cmd('G0 X1')).toEqual([expect.stringMatching(/^ok/)]);
    expect(h.cmd('M828')[0]).toMatch(/^echo:Streaming/); // and a new stream can begin
  });

  it('M112 ends a stream at once: LEDs off, halted, its records refused', () => {
    const j = job(GEOMETRIES.adjacent, 'serpentine', [24, 80], 0.4);
    const { h } = noSdPrinter(j);
    h.cmd('M828');
    const records = encodeJob(j).trimEnd().split('\n');
    records.slice(0, 30).forEach((r) => send(h, r));
    h.cmd('M112');
    expect(h.sim.nano.lit).toBe(0);
    expect(h.cmd(records[30])[0]).toMatch(/^(Error:E13|echo:E10)/);
    expect(h.cmd('M828')[0]).toMatch(/^Error:E13/);
  });
});
