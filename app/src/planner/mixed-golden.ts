// Golden mixed cases: random jobs whose rows are dense in places and sparse in others, so their plans
// take both ways. `npm run vectors:planner` writes them to protocol/vectors/mixed-ts.json.

import type { PrintJob } from '../protocol/job-types';
import { GEOMETRIES, MACHINE, RAISED_MACHINE, randomJob } from './golden';
import { headerOf } from './job-header';
import { mixedVector, planMixed } from './mixed';
import { SLOW_MACHINE } from './scan-golden';
import type { MotionModel } from './time-model';

export interface MixedCase {
  name: string;
  job: PrintJob;
  machine: MotionModel;
  mixed: object;
}

export function mixedCase(name: string, job: PrintJob, machine: MotionModel): MixedCase {
  if ('targetUJcm2' in job.dose) job.dose.targetUJcm2 = Math.ceil(job.dose.targetUJcm2 / 1000);
  return { name, job, machine, mixed: mixedVector(planMixed({ header: headerOf(job), cells: job.gridData }, machine)) };
}

/** A job whose every `sparseEvery`-th band of rows keeps only a few far-apart cells. */
export function patchyJob(seed: number, offsets: [number, number][], size: [number, number], sparseEvery: number): PrintJob {
  const j = randomJob(seed, offsets, 'mixed', size, 0.85);
  j.gridData.forEach((row, y) => {
    if (Math.floor(y / 2) % sparseEvery !== 0) return;
    const r = row as number[];
    for (let x = 0; x < r.length; x++) if ((x * 13 + y * 5 + seed) % 23 !== 0) r[x] = 0;
  });
  return j;
}

export function mixedGoldenCases(): MixedCase[] {
  const out: MixedCase[] = [];
  let seed = 5000;
  for (const [g, offsets] of Object.entries(GEOMETRIES)) {
    for (let n = 0; n < 4; n++) {
      const j = patchyJob(seed++, offsets, [50 + n * 10, 10 + n * 3], 2 + (n % 2));
      if (n < 2) j.dose = { map: 'threshold', level: 100, fullUs: 1500 + n * 700 };
      out.push(mixedCase(`ts mixed ${g} #${n}`, j, n % 2 ? SLOW_MACHINE : MACHINE));
    }
    out.push(mixedCase(`ts mixed ${g} random`, randomJob(seed++, offsets, 'mixed'), MACHINE));
  }
  // Dense and sparse rows on the raised link: its scan passes are capped less.
  for (const [g, offsets] of Object.entries(GEOMETRIES)) {
    const j = patchyJob(seed++, offsets, [60, 12], 2);
    j.dose = { map: 'threshold', level: 100, fullUs: 1500 };
    out.push(mixedCase(`ts mixed ${g}, link at 250000`, j, RAISED_MACHINE));
  }
  return out;
}
