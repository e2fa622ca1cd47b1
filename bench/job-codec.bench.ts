// B1: encoding job text for a 1 M-cell job, against a plain pass over the same cells. The app writes job
// text and only the firmware reads it, so the verifier's speed is the Mega's (its upload, mega.md M28).
import { encodeJob } from '../app/src/protocol/job-encode';
import type { PrintJob } from '../app/src/protocol/job-types';
import { compare, type Row } from './harness';
import { pcbMask } from './masks';

export function jobCodecBench(): Row[] {
  const mask = pcbMask(1024, 1024);
  const job: PrintJob = {
    grid: { cols: mask.cols, rows: mask.rows },
    pitchUm: { x: 100, y: 100 },
    originUm: { x: 0, y: 0 },
    dose: { map: 'threshold', level: 128, fullUs: 4000 },
    leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'serpentine' },
    gridData: mask.cells,
  };
  let sink = 0;
  return compare('B1 job encoder, 1 M cells (PCB-like 1024x1024)', { name: 'baseline: one pass summing every cell', run: () => {
    for (const row of mask.cells) for (let i = 0; i < row.length; i++) sink += row[i];
  } }, [
    { name: 'encode job text (segments + CRC-32)', run: () => void encodeJob(job) },
  ]);
}
