// Golden scan cases: random small jobs over several geometries and machines, with the scan plan this
// implementation makes. `npm run vectors:planner` writes them to protocol/vectors/scan-ts.json.

import type { PrintJob } from '../protocol/job-types';
import { GEOMETRIES, MACHINE, RAISED_MACHINE, randomJob } from './golden';
import { headerOf } from './job-header';
import { planScan, type ScanPlan } from './scan';
import type { MotionModel } from './time-model';

/** A machine whose X maximum caps the speed of most jobs. */
export const SLOW_MACHINE: MotionModel = { ...MACHINE, vmaxUmS: [9000, 100_000], accelUmS2: [700_000, 2_000_000], startUm: [3000, 500], stepsMilli: [80_000, 100_000] };

export interface ScanCase {
  name: string;
  job: PrintJob;
  machine: MotionModel;
  scan: ScanPlan;
}

export function scanCase(name: string, job: PrintJob, machine: MotionModel): ScanCase {
  // Keep a window under a second or so, as real doses are: random targets make minutes.
  if ('targetUJcm2' in job.dose) job.dose.targetUJcm2 = Math.ceil(job.dose.targetUJcm2 / 1000);
  return { name, job, machine, scan: planScan({ header: headerOf(job), cells: job.gridData }, machine) };
}

export function scanGoldenCases(): ScanCase[] {
  const out: ScanCase[] = [];
  let seed = 3000;
  for (const [g, offsets] of Object.entries(GEOMETRIES)) {
    for (let n = 0; n < 4; n++) out.push(scanCase(`ts scan ${g} #${n}`, randomJob(seed++, offsets, 'serpentine'), n % 2 ? SLOW_MACHINE : MACHINE));
    out.push(scanCase(`ts scan ${g} wide`, randomJob(seed++, offsets, 'serpentine', [70, 12]), MACHINE));
    out.push(scanCase(`ts scan ${g} sparse`, randomJob(seed++, offsets, 'serpentine', [60, 30], 0.03), SLOW_MACHINE));
  }
  // Full cells at uncapped speed fill their windows: runs merge into one interval per LED.
  for (const [g, offsets] of Object.entries(GEOMETRIES)) {
    const j = randomJob(seed++, offsets, 'serpentine', [40, 10], 0.8);
    j.dose = { map: 'threshold', level: 100, fullUs: 1500 + (seed % 7) * 113 };
    j.leds.gainPermille = [1000, 1000, 1000, 1000];
    out.push(scanCase(`ts scan ${g} runs`, j, MACHINE));
  }
  // More blank stretches a pass than it flies (MAX_JUMPS): the longest are kept, the lower column
  // first among equals. Random gaps, then equal ones, each in both directions (two passes).
  for (const [g, offsets] of Object.entries(GEOMETRIES)) {
    const j = randomJob(seed++, offsets, 'serpentine', [400, 8], 0.02);
    j.dose = { map: 'threshold', level: 100, fullUs: 2000 };
    out.push(scanCase(`ts scan ${g} many stretches`, j, MACHINE));
  }
  const even = randomJob(seed++, GEOMETRIES.adjacent, 'serpentine', [241, 8], 0);
  even.dose = { map: 'threshold', level: 100, fullUs: 2000 };
  for (const y of [0, 5]) for (let x = 3; x < 241; x += 20) (even.gridData[y] as number[])[x] = 255;
  out.push(scanCase('ts scan equal stretches', even, MACHINE));
  // Photos in many gray levels at a speed whose program lines would outrun the printhead link: the
  // link cap lays their passes out again at longer windows (planner.md "The printhead link").
  for (const [g, offsets] of Object.entries(GEOMETRIES)) {
    const j = randomJob(seed++, offsets, 'serpentine', [40 + (seed % 40), 4 + (seed % 6)], 0.9);
    j.dose = { map: 'linear', fullUs: 1000 + (seed % 17) * 113 };
    out.push(scanCase(`ts scan ${g} photo, link-capped`, j, MACHINE));
    out.push(scanCase(`ts scan ${g} photo, link at 250000`, structuredClone(j), RAISED_MACHINE));  // capped less
  }
  // The simavr scan test's dense pass (scan_dose.h testPattern's rows 8 to 11, 100 µm at 1 ms a
  // cell): a chain of four programs whose third would come late at the window the whole chain's
  // rule gives, so each program's own rule slows it further.
  const simavr: MotionModel = { ...MACHINE, vmaxUmS: [100_000, 100_000], accelUmS2: [2_000_000, 1_500_000], overheadUs: 400 };
  out.push(scanCase('ts scan four programs, each in time', testPatternJob(8, 12), simavr));
  // The same at 250000 baud: the Mega's 300 µs an event, not the wire, now sets the window.
  out.push(scanCase('ts scan four programs, link at 250000', testPatternJob(8, 12), { ...simavr, linkBaud: 250000 }));
  return out;
}

/** Rows `from` to `to` − 1 of the simavr tests' pattern (firmware/mega/src/scan_dose.h testPattern, 40 columns). */
function testPatternJob(from: number, to: number): PrintJob {
  const gridData: number[][] = [];
  for (let r = from; r < to; r++) {
    gridData.push(Array.from({ length: 40 }, (_, c) => (r % 3 === 0 ? (c % 2 ? 255 : 0) : r % 3 === 1 ? (Math.floor(c / 4) % 2 ? 255 : 0) : (c * 41 + r * 13) % 256)));
  }
  return {
    grid: { cols: 40, rows: to - from }, pitchUm: { x: 100, y: 100 }, originUm: { x: 5000, y: 4000 },
    dose: { map: 'linear', fullUs: 1000 }, leds: { offsets: GEOMETRIES.adjacent, gainPermille: [1000, 1000, 1000, 1000] }, strategy: { name: 'serpentine' },
    gridData,
  };
}
