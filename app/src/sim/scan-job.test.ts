import { describe, expect, it } from 'vitest';
import { encodeJob } from '../protocol/job-encode';
import type { PrintJob } from '../protocol/job-types';
import { SimHost } from './sim-host.fixture';

/** A PCB-like mask: 1-cell tracks, pads, a gray wedge and blank stretches the head flies over. */
function boardJob(cols = 72, rows = 20): PrintJob {
  const grid = Array.from({ length: rows }, () => new Array<number>(cols).fill(0));
  for (let y = 0; y < rows; y++) {
    for (let x = 0; x < cols; x++) {
      if (y % 5 === 2 && x > 3 && x < 40) grid[y][x] = 255; // horizontal tracks
      if (x === 10 || x === 11 + (y % 3)) grid[y][x] = 255; // a vertical track with a jog
      if (x >= 50 && x < 54 && y >= 4 && y < 8) grid[y][x] = 200; // a pad
      if (x >= 60 && y === 14) grid[y][x] = Math.round(((x - 60) * 255) / (cols - 61)); // a gray wedge
    }
  }
  grid[17][70] = 1; // a lone faint dot after a long blank stretch
  return {
    grid: { cols, rows },
    pitchUm: { x: 50, y: 50 },
    originUm: { x: 20000, y: 30000 },
    dose: { map: 'linear', fullUs: 4000 },
    leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'scan' },
    gridData: grid,
  };
}

function started(job = boardJob()) {
  const h = new SimHost();
  h.cmd('G28');
  h.upload('S.UVJ', encodeJob(job));
  h.cmd('M23 S.UVJ');
  const { plan, scan } = h.sim.mega.job;
  if (!scan || !plan) throw new Error('not planned as a scan job');
  h.cmd('M24');
  return { h, plan, scan, start: h.sim.clock.now };
}

const onTime = (leds: [number, number][][]) => leds.map((l) => l.reduce((s, [on, off]) => s + off - on, 0));

describe('simulated printer: scan jobs (exposure on the move)', () => {
  it("runs a board within 2 % of the scan planner's estimate, each pass once, the LEDs switched at the plan's times", () => {
    const { h, plan, scan, start } = started();
    expect(scan.passes.length).toBeGreaterThan(3);
    expect(scan.passes.some((p) => p.jumps.length > 0)).toBe(true); // the board has stretches worth flying
    const onBefore = [...h.sim.nano.onUs];
    h.waitFor(/^JOB:done/);
    const took = h.sim.clock.now - start;
    console.log(`[scan sim] ${scan.passes.length} passes at ${scan.speedUmS / 1000} mm/s: ${took} µs run, ${scan.estimateUs} µs estimated`);
    expect(plan.estimateUs).toBe(scan.estimateUs);
    expect(Math.abs(took - scan.estimateUs) / scan.estimateUs).toBeLessThanOrEqual(0.02);
    const runs = h.sim.mega.job.scanExposures;
    expect(runs.map((r) => r.pass)).toEqual(scan.passes.map((_, i) => i));
    runs.forEach((r, i) => expect(r.leds).toEqual(scan.passes[i].leds));
    // The printhead's own on-time counters agree with the plan's intervals.
    const planned = [0, 1, 2, 3].map((k) => scan.passes.reduce((s, p) => s + onTime(p.leds)[k], 0));
    expect(h.sim.nano.onUs.map((t, k) => t - onBefore[k])).toEqual(planned);
    expect(h.cmd('M1000 S')[0]).toBe('JOB:idle');
    // Its time as reported stays the job's time once it has ended, as the Mega counts it.
    h.sim.advance(5000);
    expect(h.cmd('M27')[0]).toContain(` elapsed=${Math.floor(took / 1e6)} `);
  });

  it('reports progress per pass', () => {
    const { h, scan } = started();
    while (h.sim.mega.job.scanExposures.length < 1) h.sim.advance(1);
    expect(h.cmd('M27')[0]).toMatch(new RegExp(`^JOB:running .*stop=1/${scan.passes.length} `));
    while (h.sim.mega.job.scanExposures.length < 2) h.sim.advance(1);
    expect(h.cmd('M27')[0]).toMatch(new RegExp(`^JOB:running .*stop=2/${scan.passes.length} `));
  });

  it('aborts mid-pass with the LEDs off at once and the head stopped', () => {
    const { h } = started();
    while (h.sim.nano.lit === 0) h.sim.advance(1);
    expect(h.sim.mega.motion.moving).toBe(true);
    h.cmd('M524');
    expect(h.sim.nano.lit).toBe(0);
    expect(h.sim.mega.motion.moving).toBe(false);
    expect(h.cmd('M27')[0]).toMatch(/^JOB:aborted/);
    const on = [...h.sim.nano.onUs];
    h.sim.advance(3000);
    expect(h.sim.nano.onUs).toEqual(on);
    expect(h.cmd('M1000 S')[0]).toBe('JOB:idle');
  });

  it('pauses at the end of the pass under way, and goes on to expose every pass once', () => {
    const { h, scan } = started();
    while (h.sim.nano.lit === 0) h.sim.advance(1);
    h.cmd('M25');
    h.waitFor(/^JOB:paused/);
    expect(h.sim.nano.lit).toBe(0);
    const n = h.sim.mega.job.scanExposures.length;
    expect(n).toBeGreaterThan(0); // the pass under way was finished, not cut
    h.sim.advance(2000);
    expect(h.sim.mega.job.scanExposures.length).toBe(n);
    h.cmd('M24');
    h.waitFor(/^JOB:done/);
    expect(h.sim.mega.job.scanExposures.map((r) => r.pass)).toEqual(scan.passes.map((_, i) => i));
  });

  it('pauses with the LEDs off when the head is stopped under a pass (M410), and exposes that pass again', () => {
    const { h, scan } = started();
    while (h.sim.mega.job.scanExposures.length < 1) h.sim.advance(1);
    while (h.sim.nano.lit === 0) h.sim.advance(1); // mid-pass 2
    h.cmd('M410');
    expect(h.sim.nano.lit).toBe(0);
    expect(h.cmd('M27')[0]).toMatch(/^JOB:paused .*reason=stopped/);
    const on = [...h.sim.nano.onUs];
    h.sim.advance(2000);
    expect(h.sim.nano.onUs).toEqual(on);
    h.cmd('M24');
    h.waitFor(/^JOB:done/);
    expect(h.sim.mega.job.scanExposures.map((r) => r.pass)).toEqual(scan.passes.map((_, i) => i));
  });

  it('exposes a pass cut by a power cut again on resume', () => {
    const { h, scan } = started();
    while (h.sim.mega.job.scanExposures.length < 2) h.sim.advance(1);
    while (h.sim.nano.lit === 0) h.sim.advance(1); // mid-pass 3
    const before = h.sim.mega.job.scanExposures.map((r) => r.pass);
    h.sim.powerCycle();
    h.reconnect();
    expect(h.cmd('M1000 S')[0]).toBe(`JOB:interrupted file=S.UVJ stop=2/${scan.passes.length}`);
    h.cmd('G28');
    expect(h.cmd('M1000').join('\n')).toMatch(/^echo:resume: stop 2 .*is exposed again$/m);
    h.waitFor(/^JOB:done/);
    const after = h.sim.mega.job.scanExposures.map((r) => r.pass);
    expect([...before, ...after]).toEqual(scan.passes.map((_, i) => i));
  });

  it('stops a pass on over-temperature with the LEDs off, and the pass is not counted', () => {
    const h = new SimHost({ nano: { heatingCPerS: 1500 } });
    h.cmd('G28');
    h.upload('H.UVJ', encodeJob(boardJob()));
    h.cmd('M23 H.UVJ');
    h.cmd('M24');
    h.waitFor(/^FAULT:E31/, 120_000);
    expect(h.sim.nano.lit).toBe(0);
    expect(h.sim.mega.motion.moving).toBe(false);
    expect(h.cmd('M27')[0]).toMatch(/^JOB:paused .*reason=overtemp/);
    expect(h.sim.mega.job.scanExposures).toHaveLength(0);
  });

  it('streams a scan job (M828): each pass exposed once its rows have come, its light at the times the whole plan gives', () => {
    const job = boardJob();
    const card = new SimHost();
    card.cmd('G28');
    card.upload('S.UVJ', encodeJob(job));
    card.cmd('M23 S.UVJ');
    const whole = card.sim.mega.job.scan!;
    const h = new SimHost();
    h.cmd('G28');
    const out = [...h.cmd('M828')];
    const records = encodeJob(job).trimEnd().split('\n');
    let passesWhileStreaming = 0;
    records.forEach((r, i) => {
      out.push(...h.cmd(r));
      if (i !== records.length >> 1) return;
      h.sim.advance(400_000); // the host pauses half-way: the passes whose rows have come run meanwhile
      passesWhileStreaming = h.sim.mega.job.scanExposures.length;
    });
    out.push(...h.cmd('M29'));
    expect(out.filter((l) => /^(echo:)?E\d/.test(l))).toEqual([]);
    h.waitFor(/^JOB:done/);
    expect(passesWhileStreaming, 'passes exposed before the last record came').toBeGreaterThan(0);
    expect(passesWhileStreaming).toBeLessThan(whole.passes.length);
    const runs = h.sim.mega.job.scanExposures;
    expect(runs.map((r) => r.pass)).toEqual(whole.passes.map((_, i) => i));
    runs.forEach((r, i) => expect(r.leds).toEqual(whole.passes[i].leds));
  });
});
