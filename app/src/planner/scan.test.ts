// Scan mode's properties (protocol/planner.md "Scan mode"), checked on the app's planner: the C++ planner as WebAssembly.
import { describe, expect, it } from 'vitest';
import type { PrintJob } from '../protocol/job-types';
import { durationTables } from './dose';
import { headerOf } from './job-header';
import type { ScanPlan } from './plan';
import type { JobHeader } from '../protocol/job-types';
import { axisSteps, engineMoveUs, moveTimeUs, planJob, planScan } from './planner-wasm';
import { GEOMETRIES, MACHINE, randomJob } from './test-jobs';
import type { MotionModel } from './time-model';

/** The blank stretches a pass flies at most (scan.h kMaxJumps). */
const MAX_JUMPS = 8;

/** The fly of g blank windows on MACHINE at 50 µm, 2000 µs windows (planner.md "Blank stretches"). */
const F = (g: number) => Math.max(1, moveTimeUs(g * 50 + 2 * 105, 150000, 3000000) - 2 * 8334);

const plan = (job: PrintJob, machine: MotionModel = MACHINE) => planScan({ header: headerOf(job), cells: job.gridData }, machine);

/**
 * `m` with as many X steps a mm as make the job's step 1 ms, so the step engine runs any window: the
 * properties of the light hold whatever the machine, and random doses make windows of seconds.
 */
const runnable = (j: PrintJob, m: MotionModel): MotionModel => ({ ...m, stepsMilli: [Math.max(1, Math.round((1000 * plan(j, m).windowUs) / j.pitchUm.x)), m.stepsMilli[1]] });

/**
 * The test's own reading of protocol/planner.md "Passes": the row each pass gives each LED, or -1, in
 * the order the passes open (every row once, to the first pass that reaches it).
 */
function passRows(h: JobHeader, rows: ArrayLike<number>[]): { hy: number; ledRows: number[] }[] {
  const dy = h.offsets.map((o) => o[1]);
  const dyMin = Math.min(...dy);
  const covered = new Uint8Array(h.rows);
  const out: { hy: number; ledRows: number[] }[] = [];
  for (let r = 0; r < h.rows; r++) {
    if (covered[r] || !Array.from(rows[r]).some((v) => v > 0)) continue;
    const hy = r - dyMin;
    const ledRows = [-1, -1, -1, -1];
    for (let k = 0; k < 4; k++) {
      const rk = hy + dy[k];
      if (rk < 0 || rk >= h.rows || covered[rk]) continue;
      covered[rk] = 1;
      ledRows[k] = rk;
    }
    out.push({ hy, ledRows });
  }
  return out;
}

/** A job on a blank grid with the given lit cells [col, row, value]. */
function job(cols: number, rows: number, lit: [number, number, number][], over: Partial<PrintJob> = {}): PrintJob {
  const gridData = Array.from({ length: rows }, () => new Array<number>(cols).fill(0));
  for (const [c, r, v] of lit) gridData[r][c] = v;
  return {
    grid: { cols, rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 1000, y: 2000 },
    dose: { map: 'linear', fullUs: 2000 }, leds: { offsets: GEOMETRIES.adjacent }, strategy: { name: 'serpentine' },
    gridData, ...over,
  };
}

/** Each cell's on-time, read back from the switch lists: the part of each interval inside each window. */
function doses(j: PrintJob, p: ScanPlan): Map<string, [number, number]> {
  const out = new Map<string, [number, number]>();
  for (const pass of p.passes) {
    const W = pass.windowUs;
    // Window starts: W apart, but a jump [first blank window, g, µs] takes its µs for its g windows.
    const S: number[] = [];
    for (let w = 0, t = 0; w <= pass.last - pass.first; w++) {
      const jump = pass.jumps.find(([at]) => at === w);
      if (jump) {
        t += jump[2];
        w += jump[1] - 1;
        continue;
      }
      S.push(w, t);
      t += W;
    }
    pass.leds.forEach((list, k) => {
      let end = -1;
      for (const [on, off] of list) {
        expect(on, 'intervals in time order, apart').toBeGreaterThan(end);
        expect(off).toBeGreaterThan(on);
        end = off;
        for (let i = 0; i < S.length; i += 2) {
          const w = S[i], t = Math.min(off, S[i + 1] + W) - Math.max(on, S[i + 1]);
          if (t <= 0) continue;
          const hx = pass.descending ? pass.last - w : pass.first + w;
          const key = `${hx + j.leds.offsets[k][0]},${pass.hy + j.leds.offsets[k][1]}`;
          const had = out.get(key);
          if (had) expect(had[1], `${key} lit by two LEDs`).toBe(k);
          out.set(key, [(had?.[0] ?? 0) + t, k]);
        }
      }
    });
  }
  return out;
}

describe('scan planner', () => {
  it('gives every lit cell its stop-mode dose to the µs, once, and nothing else', () => {
    let cells = 0;
    for (const offsets of Object.values(GEOMETRIES)) {
      for (let seed = 0; seed < 40; seed++) {
        const j = randomJob(5000 + seed, offsets, 'serpentine');
        const tables = durationTables(headerOf(j));
        const p = plan(j, runnable(j, seed % 3 ? MACHINE : { ...MACHINE, vmaxUmS: [2000, 2000] }));
        expect(p.passes.length, 'a plan').toBeGreaterThan(0);
        const got = doses(j, p);
        const owner = new Array<number>(j.grid.rows).fill(-1); // the LED its pass gives each row
        for (const { ledRows } of passRows(headerOf(j), j.gridData)) ledRows.forEach((r, k) => r >= 0 && (owner[r] = k));
        j.gridData.forEach((row, r) =>
          Array.from(row).forEach((v, c) => {
            const k = owner[r];
            const [d, by] = got.get(`${c},${r}`) ?? [0, k];
            if (d) cells++;
            expect([d, by], `cell ${c},${r} value ${v}`).toEqual([k >= 0 ? tables[k][v] : 0, k]);
            got.delete(`${c},${r}`);
          }),
        );
        expect([...got.keys()], 'light outside the grid').toEqual([]);
        p.passes.forEach((pass, i) => expect(pass.descending).toBe(i % 2 === 1));
      }
    }
    expect(cells).toBeGreaterThan(5000);
  });

  it('exposes the rows in the passes of the stop planner, serpentine', () => {
    for (const offsets of Object.values(GEOMETRIES)) {
      for (let seed = 0; seed < 20; seed++) {
        const j = randomJob(7000 + seed, offsets, 'serpentine');
        const stops = planJob({ header: headerOf(j), cells: j.gridData }, MACHINE);
        const rows = [...new Set(stops.hy)];
        expect(plan(j, runnable(j, MACHINE)).passes.map((p) => p.hy)).toEqual(rows);
        expect(plan(j, runnable(j, MACHINE)).passes.map((p) => p.descending)).toEqual(rows.map((_, i) => i % 2 === 1));
      }
    }
  });

  it('centres a one-cell feature in its window, at the window, speed and overscan of the protocol', () => {
    const p = plan(job(10, 4, [[3, 0, 255]]));
    expect([p.windowUs, p.speedUmS]).toEqual([2000, 25000]);
    // tA = ceil(50e12 / (3e6 × 2000)) = 8334 µs; o = ceil(50 × 8334 / 4000) = 105 µm.
    expect([p.accelUs, p.overscanUm]).toEqual([8334, 105]);
    const [pass] = p.passes;
    expect(pass).toMatchObject({ hy: 0, descending: false, first: 3, last: 3, windowUs: 2000, accelUs: 8334, overscanUm: 105, runUpUm: 1000 + 150 - 25 - 105, runOutUm: 1000 + 150 + 25 + 105, leds: [[[0, 2000]], [], [], []], jumps: [], events: [[0, 1], [2000, 0]] });
    // The stroke (planner.md "The stroke"), at 80 steps/mm: 4 steps a window, 500 µs a step (q = 1000
    // ticks), 2000 steps/s reached in R = ceil(2000² / (2 × 240000)) = 9 steps. The mark, X 1125 µm, is
    // step 90; the G step 4 before it (ceil(2340 / 1000) + 1), after R + 2 steps from the start: 75.
    // The last window ends at step 94; the stroke R + 1 steps later, at 104.
    expect([pass.startSteps, pass.stopSteps]).toEqual([75, 104]);
    // From X 0 (step 0) and Y 0 to step 75 and Y 2000 µm (160 steps): the step engine's move.
    expect(pass.moveUs).toBe(engineMoveUs(MACHINE, 75, axisSteps(MACHINE, 1, 2000)));
    // 11 steps at 500 µs between the ramps, each some 0.7 ms quicker than the continuous 2000 / 240000 s
    // (the engine's first step goes at once, each segment at the rate at its middle).
    expect(pass.strokeUs).toBe(20772);
    expect(pass.strokeUs).toBeGreaterThan(11 * 500 + 2 * 7500);
    expect(pass.strokeUs).toBeLessThan(11 * 500 + 2 * 8334);
    expect(p.estimateUs).toBe(pass.wallUs); // the move, the pass's load, the stroke, the Q that ends it
    expect(pass.wallUs).toBeGreaterThan(pass.moveUs + pass.strokeUs);
  });

  it('writes gray levels as on-time within the window, and merges only runs that fill their windows', () => {
    const p = plan(job(10, 4, [[2, 0, 255], [3, 0, 255], [4, 0, 128], [5, 0, 255], [2, 1, 51], [3, 1, 51]]));
    // t(128) = round(2000 × 128 / 255) = 1004: (2000 − 1004) / 2 = 498 µs in. t(51) = 400.
    expect(p.passes[0].leds[0]).toEqual([[0, 4000], [4000 + 498, 4000 + 498 + 1004], [6000, 8000]]);
    expect(p.passes[0].leds[1]).toEqual([[800, 1200], [2800, 3200]]);
    // As the Nano runs it: LED 0 stays on from 0 to 4000 across the boundary of two full cells.
    expect(p.passes[0].events).toEqual([[0, 1], [800, 3], [1200, 1], [2800, 3], [3200, 1], [4000, 0], [4498, 1], [5502, 0], [6000, 1], [8000, 0]]);
  });

  it('reverses the second pass: windows count from the last column, times mirror', () => {
    const p = plan(job(12, 8, [[2, 0, 255], [9, 0, 51], [3, 4, 51], [10, 4, 255], [10, 5, 102]]));
    const [a, b] = p.passes;
    expect([a.descending, a.first, a.last]).toEqual([false, 2, 9]);
    expect(F(6)).toBeLessThanOrEqual(5 * 2000); // six blank windows: the fly saves at least a window
    expect(a.jumps).toEqual([[1, 6, F(6)]]);
    expect(a.leds[0]).toEqual([[0, 2000], [2000 + F(6) + 800, 2000 + F(6) + 1200]]);
    expect([b.hy, b.descending, b.first, b.last]).toEqual([4, true, 3, 10]);
    expect(b.jumps).toEqual([[1, 6, F(6)]]);
    expect(b.leds[0]).toEqual([[0, 2000], [2000 + F(6) + 800, 2000 + F(6) + 1200]]);
    expect(b.leds[1]).toEqual([[600, 1400]]); // t(102) = 800
    expect([b.runUpUm, b.runOutUm]).toEqual([1000 + 10 * 50 + 25 + 105, 1000 + 3 * 50 - 25 - 105]);
  });

  it('places each LED by its own column offset, negative ones too', () => {
    const offsets: [number, number][] = [[0, 0], [-3, 1], [4, 2], [-1, 3]];
    const p = plan(job(12, 4, [[5, 0, 255], [5, 1, 255], [5, 2, 255], [5, 3, 255]], { leds: { offsets } }));
    const [pass] = p.passes;
    // Head columns 5, 8, 1, 6: the pass runs from 1 to 8, lit in windows 0, 4, 5 and 7.
    expect([pass.first, pass.last]).toEqual([1, 8]);
    // Each fly beats crossing at the speed (2000, 6000 µs), but by less than a window: neither is flown.
    expect([F(1), F(3)]).toEqual([1950, 5240]);
    expect(pass.jumps).toEqual([]);
    const S4 = 8000, S5 = 10000, S7 = 14000;
    expect(pass.leds).toEqual([[[S4, S4 + 2000]], [[S7, S7 + 2000]], [[0, 2000]], [[S5, S5 + 2000]]]);
    expect(p.estimateUs).toBe(pass.wallUs); // the move, the pass's load, the stroke, the Q that ends it
    expect(pass.wallUs).toBeGreaterThan(pass.moveUs + pass.strokeUs);
    expect(pass.strokeUs - pass.markUs).toBeGreaterThan(S7 + 2000); // the mark, then the windows, then the ramp down
  });

  it('flies no blank stretch when the speed is capped, and one only when it saves a window', () => {
    const slow = { ...MACHINE, vmaxUmS: [10000, 100000] as [number, number] };
    expect(plan(job(40, 4, [[2, 0, 255], [30, 0, 255]]), slow).passes[0].jumps).toEqual([]);
    // A slow axis: a fly of one window would take longer than the window.
    const lazy = { ...MACHINE, accelUmS2: [300000, 2000000] as [number, number] };
    const p = plan(job(40, 4, [[2, 0, 255], [4, 0, 255], [30, 0, 255]]), lazy);
    expect(p.passes[0].jumps.map((j) => j.slice(0, 2))).toEqual([[3, 25]]);
  });

  it('flies only the MAX_JUMPS longest stretches of a pass, the lower column first among equals, both ways', () => {
    const gaps = [10, 20, 12, 30, 12, 40, 9, 50, 12, 15, 12];
    const lit: [number, number, number][] = [[2, 0, 255], [2, 4, 255]];
    const lows: number[] = [];
    let c = 2;
    for (const g of gaps) {
      lows.push(c + 1);
      c += g + 1;
      lit.push([c, 0, 255], [c, 4, 255]);
    }
    const kept = [1, 2, 3, 4, 5, 7, 8, 9].map((i) => `${lows[i]}+${gaps[i]}`).sort();
    const p = plan(job(240, 8, lit));
    expect(p.passes.map((q) => q.descending)).toEqual([false, true]);
    for (const q of p.passes) {
      expect(q.jumps.length).toBe(MAX_JUMPS);
      const flown = q.jumps.map(([w, g]) => `${q.descending ? q.last - w - g + 1 : q.first + w}+${g}`).sort();
      expect(flown).toEqual(kept);
      const saved = q.jumps.reduce((t, [, g, f]) => t + g * 2000 - f, 0);
      expect(q.leds[0].at(-1)?.[1]).toBe((q.last - q.first + 1) * 2000 - saved);
    }
  });

  it('never flies for a machine that cannot: the same light, every window W after the last, a longer estimate', () => {
    const j = job(200, 4, [[3, 0, 200], [4, 0, 200], [60, 0, 200], [150, 0, 200], [199, 0, 200]]);
    const flying = plan(j);
    const crossing = planScan({ header: headerOf(j), cells: j.gridData }, MACHINE, { neverFly: true });
    expect(flying.passes[0].jumps.length).toBeGreaterThan(0);
    expect(crossing.passes[0].jumps).toEqual([]);
    expect(doses(j, crossing)).toEqual(doses(j, flying));
    const W = crossing.windowUs, on = durationTables(headerOf(j))[0][200];
    for (const [t0, t1] of crossing.passes[0].leds[0]) {
      expect(t0 % W).toBe(Math.floor((W - on) / 2)); // each in its column's window, j·W from the mark
      expect(t1 - t0).toBe(on);
    }
    expect(crossing.estimateUs).toBeGreaterThan(flying.estimateUs);
  });

  it('caps the speed at the axis maximum: longer windows, same on-times, no merging', () => {
    const slow = { ...MACHINE, vmaxUmS: [10000, 100000] as [number, number] };
    const p = plan(job(10, 4, [[2, 0, 255], [3, 0, 255], [4, 0, 128]]), slow);
    expect([p.windowUs, p.speedUmS]).toEqual([5000, 10000]);
    expect(p.passes[0].leds[0]).toEqual([[1500, 3500], [6500, 8500], [10000 + 1998, 10000 + 1998 + 1004]]);
  });

  it('plans a stream while its rows arrive: every pass whose rows have all come, a prefix of the whole plan', () => {
    for (const [name, geometry] of Object.entries(GEOMETRIES)) {
      for (let seed = 1; seed <= 6; seed++) {
        const j = randomJob(seed * 31 + name.length, geometry, 'serpentine', undefined, 0.3);
        const h = headerOf(j), whole = plan(j);
        const dyMax = Math.max(...h.offsets.map((o) => o[1]));
        let before = 0;
        for (let known = 0; known <= h.rows; known++) {
          // Rows still to come read as 0, as in the Mega's buffer.
          const cells = j.gridData.map((row, r) => (r < known ? row : new Array<number>(row.length).fill(0)));
          const part = planScan({ header: h, cells, knownRows: known }, MACHINE);
          expect(part.passes, `${name} #${seed} at ${known} rows`).toEqual(whole.passes.slice(0, part.passes.length));
          for (const p of part.passes) expect(known === h.rows || p.hy + dyMax < known).toBe(true);
          expect(part.passes.length).toBeGreaterThanOrEqual(before);
          before = part.passes.length;
        }
        expect(before).toBe(whole.passes.length);
      }
    }
  });

  it('plans nothing for a job with no lit cell', () => {
    const p = plan(job(6, 4, [[1, 1, 50]], { dose: { map: 'threshold', level: 100, fullUs: 2000 } }));
    expect([p.passes.length, p.estimateUs]).toEqual([0, 0]);
  });
});

describe('scan planner limits', () => {
  it('plans nothing when a pass would outlast a 32-bit µs timer', () => {
    const long = job(3000, 4, [[1, 0, 255]], { dose: { map: 'linear', fullUs: 1_500_000 } });
    const fine: MotionModel = { ...MACHINE, stepsMilli: [2_000_000, 80_000] }; // 100 steps a window: 15 ms a step
    expect(plan(long, fine).passes).toEqual([]);
    long.grid.cols = 2800; // 2800 × 1.5 s < 2³² µs
    long.gridData = long.gridData.map((r) => Array.from(r).slice(0, 2800));
    expect(plan(long, fine).passes.length).toBe(1);
  });

  it('plans nothing, and says why, when the step engine cannot run the speed (mega.md M29)', () => {
    // 200 ms windows at 50 µm and 80 steps/mm: 4 steps a window, 50 ms a step; the engine's longest is 32.768 ms.
    const slow = plan(job(10, 4, [[1, 0, 255]], { dose: { map: 'linear', fullUs: 200_000 } }));
    expect([slow.passes.length, slow.estimateUs]).toEqual([0, 0]);
    expect(slow.refused).toMatch(/step longer than the step engine's 32.8 ms/);
    // 131 ms makes a step of 32.75 ms: it runs.
    expect(plan(job(10, 4, [[1, 0, 255]], { dose: { map: 'linear', fullUs: 131_000 } })).passes.length).toBe(1);
    // A machine that would go faster than its steps: 100 µm in 400 µs at 400 steps/mm is 100000 steps/s.
    const fast = plan(job(10, 4, [[1, 0, 255]], { pitchUm: { x: 100, y: 50 }, dose: { map: 'linear', fullUs: 400 } }), { ...MACHINE, vmaxUmS: [250_000, 100_000], stepsMilli: [400_000, 80_000] });
    expect(fast.refused).toMatch(/over the step engine's 16000 steps\/s/);
  });
});

