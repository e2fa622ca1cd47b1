// B5: the delivered-dose map of a whole bed (100 × 80 mm at 50 µm, 2000 × 1600 cells, a PCB-like mask
// on the move), every record reported. What the page's thread carried for it before (the first
// count of a job's map, and each drawing of it: every cell binned), now the work worker's
// (work/dose-work.ts), against what the page does now for an update: the batch of changed stops,
// and its copy into the message to the worker. Baseline: one pass over every cell.
import { DoseLedger } from '../app/src/device/dose-ledger';
import { batchSince, NOTHING_HEARD } from '../app/src/job/dose-batch';
import { doseImage } from '../app/src/job/dose-colours';
import { DoseTally } from '../app/src/job/dose-map';
import { planDoses, programCount, recordOf } from '../app/src/job/dose-plan';
import type { PrintJob } from '../app/src/protocol/job-types';
import { compare, type Row } from './harness';
import { pcbMask } from './masks';
import { BENCH_MACHINE } from './planner.bench';

export function doseMapBench(): Row[] {
  const mask = pcbMask(2000, 1600);
  const job: PrintJob = {
    grid: { cols: mask.cols, rows: mask.rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 10_000, y: 10_000 },
    dose: { map: 'threshold', level: 128, fullUs: 2000 }, leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'scan' }, gridData: mask.cells,
  };
  const plan = planDoses(job, BENCH_MACHINE);
  const ledger = new DoseLedger();
  for (let s = 0; s < plan.steps; s++)
    for (let p = 0; p < programCount(plan, s); p++)
      ledger.add({ kind: 'dose', stop: s, program: p, exposure: 1, onUs: recordOf(plan, s, p).ledUs, cut: false, again: false });
  const tally = new DoseTally(plan);
  const counted = tally.update(ledger);
  let sink = 0;
  return compare(`B5 delivered-dose map, a whole bed (2000 x 1600 cells, ${plan.steps} passes, every record reported)`, { name: 'baseline: one pass over every cell', run: () => {
    for (let c = 0; c < counted.state.length; c++) sink += counted.state[c];
  } }, [
    { name: 'worker (page before): first count of the map', run: () => void new DoseTally(plan).update(ledger) },
    { name: 'worker (page before): the map binned to 480 px', run: () => void doseImage(counted, 480) },
    { name: 'page now: the whole job as one batch, copied', run: () => void structuredClone(batchSince(ledger, NOTHING_HEARD).batch) },
    { name: 'page now: one pass\'s batch, copied', run: () => {
      const heard = { lines: ledger.since(0).lines - programCount(plan, plan.steps - 1), clears: ledger.since(0).clears };
      sink += structuredClone(batchSince(ledger, heard).batch).stops.length;
    } },
  ], 5);
}
