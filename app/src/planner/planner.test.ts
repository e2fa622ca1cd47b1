// The stop planner's properties and the firmware's stop vectors (protocol/planner.md), checked on the
// app's planner: the C++ planner as WebAssembly.
import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { headerOf } from './job-header';
import { moveTimeUs, planJob } from './planner-wasm';
import { GEOMETRIES, MACHINE, planStops, randomJob, STRATEGIES, type GoldenCase } from './test-jobs';

const VECTORS = new URL('../../../protocol/vectors/', import.meta.url);

function load(file: string): GoldenCase[] {
  const dir = process.env.UV_VECTORS_DIR ? `${process.env.UV_VECTORS_DIR}/` : VECTORS;
  return JSON.parse(readFileSync(new URL(file, dir instanceof URL ? dir : `file://${dir}`), 'utf8')).cases;
}

function plan(c: Pick<GoldenCase, 'job' | 'machine'>) {
  return planJob({ header: headerOf(c.job), cells: c.job.gridData }, c.machine);
}

function stopsOf(c: Pick<GoldenCase, 'job' | 'machine'>) {
  const p = plan(c);
  return { p, stops: planStops(p) };
}

describe('planner golden vectors', () => {
  for (const file of ['planner-cpp.json']) {
    it(`reproduces every plan in ${file}`, () => {
      const cases = load(file);
      expect(cases.length).toBeGreaterThan(20);
      for (const c of cases) {
        const { p, stops } = stopsOf(c);
        expect(stops, c.name).toEqual(c.plan.stops);
        expect([p.passes, p.estimateUs, p.travelUm], c.name).toEqual([c.plan.passes, c.plan.estimateUs, c.plan.travelUm]);
      }
      console.log(`[vectors] ${file}: ${cases.length} plans checked (the C++ planner as WebAssembly)`);
    });
  }
});

/** Independent dose formula with BigInt, for the property tests. */
function expectedUs(job: GoldenCase['job'], led: number, v: number): number {
  const d = job.dose;
  const full = 'fullUs' in d ? BigInt(d.fullUs) : (BigInt(d.targetUJcm2) * 1_000_000n * 2n + BigInt(d.irradianceUWcm2[led])) / (2n * BigInt(d.irradianceUWcm2[led]));
  const m = d.map === 'linear' ? v : v >= d.level! ? 255 : 0;
  const n = full * BigInt(job.leds.gainPermille?.[led] ?? 1000) * BigInt(m);
  return Number((n * 2n + 255000n) / 510000n);
}

describe('planner properties on random jobs', () => {
  it('exposes every lit cell exactly once, at its dose, and nothing else', () => {
    let jobs = 0;
    for (const [g, offsets] of Object.entries(GEOMETRIES)) {
      for (const s of STRATEGIES) {
        for (let seed = 0; seed < 25; seed++) {
          const job = randomJob(90000 + seed * 7 + s.length, offsets, s);
          if ('fullUs' in job.dose) job.dose.fullUs = Math.max(job.dose.fullUs, 1000); // so every lit cell has t >= 1
          const { p } = stopsOf({ job, machine: MACHINE });
          const hits = job.gridData.map((row) => new Array<number>(row.length).fill(0));
          for (let i = 0; i < p.count; i++) {
            let any = false;
            for (let k = 0; k < 4; k++) {
              const us = p.durations[i * 4 + k];
              if (!us) continue;
              any = true;
              const x = p.hx[i] + offsets[k][0], y = p.hy[i] + offsets[k][1];
              expect(y >= 0 && y < job.grid.rows && x >= 0 && x < job.grid.cols, `${g} ${s}: light outside the grid`).toBe(true);
              const v = job.gridData[y][x];
              expect(v, `${g} ${s}: light on an empty cell`).toBeGreaterThan(0);
              expect(us, `${g} ${s}: cell (${x},${y}) dose`).toBe(expectedUs(job, k, v));
              hits[y][x]++;
            }
            expect(any, 'a stop with no light').toBe(true);
          }
          job.gridData.forEach((row, y) =>
            Array.from(row).forEach((v, x) => {
              const lit = job.dose.map === 'linear' ? v > 0 : v >= job.dose.level!;
              expect(hits[y][x], `${g} ${s}: cell (${x},${y}) value ${v}`).toBe(lit ? 1 : 0);
            }),
          );
          jobs++;
        }
      }
    }
    expect(jobs).toBe(400);
  });

  it('skips empty rows and empty runs: no stop without light, no pass without a stop', () => {
    const job = randomJob(5, GEOMETRIES.adjacent, 'serpentine', [30, 40]);
    job.gridData = job.gridData.map((row, y) => (y % 9 === 0 ? row : Array.from(row, () => 0)));
    const { p } = stopsOf({ job, machine: MACHINE });
    expect(p.passes).toBe(new Set(Array.from(p.hy)).size);
    expect(p.passes).toBeLessThanOrEqual(5);
  });
});

describe('planning while rows arrive (stream mode)', () => {
  it('plans a prefix of the full plan that only grows, and the whole plan once every row is in', () => {
    let grew = 0;
    for (const offsets of Object.values(GEOMETRIES)) {
      for (const s of STRATEGIES) {
        for (let seed = 0; seed < 6; seed++) {
          const job = randomJob(70000 + seed * 13 + s.length, offsets, s);
          const full = stopsOf({ job, machine: MACHINE }).stops;
          const header = headerOf(job);
          let before = 0;
          for (let known = 0; known <= header.rows; known++) {
            // Rows not yet arrived read as 0, as they do on a Mega still receiving them.
            const cells = job.gridData.map((row, r) => (r < known ? row : Array.from(row, () => 0)));
            const p = planJob({ header, cells, knownRows: known }, MACHINE);
            const stops = planStops(p);
            expect(stops, `${s} ${JSON.stringify(offsets)} seed ${seed} rows ${known}`).toEqual(full.slice(0, p.count));
            expect(p.count).toBeGreaterThanOrEqual(before);
            if (p.count > before && known < header.rows) grew++;
            before = p.count;
          }
          expect(before).toBe(full.length);
        }
      }
    }
    expect(grew).toBeGreaterThan(50); // stops really do become final before the last row arrives
  });
});

describe('time model', () => {
  it('uses the trapezoid or the triangle as the distance allows', () => {
    expect(moveTimeUs(0, 150000, 3000000)).toBe(0);
    expect(moveTimeUs(100, 150000, 3000000)).toBe(2 * 5773); // 2 * isqrt(100e12 / 3e6)
    expect(moveTimeUs(100000, 150000, 3000000)).toBe(666667 + 50000); // d/v + v/a
    const at = 150000 ** 2 / 3000000; // 7500 µm: both formulas meet here
    expect(Math.abs(moveTimeUs(at, 150000, 3000000) - moveTimeUs(at - 1, 150000, 3000000))).toBeLessThan(20);
  });
});
