// What each dose record of a job should give, and to which cells (protocol/mega.md "Dose reports"):
// a stop's F its cells' durations; a pass on the move, program by program, the light of the events
// the chain gives that program (protocol/nano.md "Scan programs": 64 events a program), cut at the
// program's time 0 and its last event as the Nano counts a record's light.

import { headerOf } from '../planner/job-header';
import { planAnyJob, type JobPlan } from '../planner/job-plan';
import type { ScanPass } from '../planner/scan';
import type { Machine } from '../planner/time-model';
import { scanDoses } from '../preview/scan-preview';
import type { PrintJob } from '../protocol/job-types';
import { PROGRAM_EVENTS } from '../protocol/scan-program';

/** One record's planned light: each LED's on-time, and the cells it falls on (row × cols + col) with their µs. */
export interface PlannedRecord {
  ledUs: number[];
  cell: number[];
  led: number[];
  us: number[];
}

export interface DosePlan {
  cols: number;
  rows: number;
  /** steps[stop][program]: a stop has one record (program 0), a pass on the move one a program. */
  steps: PlannedRecord[][];
  /** What a step is called to a person: a stop, a pass on the move, or (mixed) either. */
  unit: 'stop' | 'pass' | 'step';
}

/** The record of one F: each LED's duration, on the cell under it (cells off the grid get none). */
export function stopRecord(job: PrintJob, hx: number, hy: number, durations: ArrayLike<number>): PlannedRecord {
  const { cols, rows } = job.grid;
  const r: PlannedRecord = { ledUs: [0, 1, 2, 3].map((k) => durations[k] ?? 0), cell: [], led: [], us: [] };
  r.ledUs.forEach((us, k) => {
    const [dx, dy] = job.leds.offsets[k] ?? [0, 0];
    const x = hx + dx, y = hy + dy;
    if (us > 0 && x >= 0 && y >= 0 && x < cols && y < rows) r.cell.push(y * cols + x), r.led.push(k), r.us.push(us);
  });
  return r;
}

/** [from, to] µs after the mark of each program of a pass's chain: time 0 (or the previous program's last event) to its own last event. */
export function programSpans(pass: Pick<ScanPass, 'events'>): [number, number][] {
  const spans: [number, number][] = [];
  const n = pass.events.length;
  for (let start = 0, from = 0; start < n; start += PROGRAM_EVENTS) {
    const to = pass.events[Math.min(start + PROGRAM_EVENTS, n) - 1][0];
    spans.push([from, to]);
    from = to;
  }
  return spans;
}

/** A pass on the move's records, one a program: each LED's intervals cut to the program's span, and the cells they light. */
export function passRecords(job: PrintJob, pass: ScanPass): PlannedRecord[] {
  return programSpans(pass).map(([from, to]) => {
    const leds = pass.leds.map((intervals) =>
      intervals.flatMap(([on, off]): [number, number][] => (off > from && on < to ? [[Math.max(on, from), Math.min(off, to)]] : [])),
    );
    const d = scanDoses(job, { passes: [{ ...pass, leds }] } as Parameters<typeof scanDoses>[1]);
    return {
      ledUs: leds.map((intervals) => intervals.reduce((sum, [on, off]) => sum + off - on, 0)),
      cell: Array.from(d.cell),
      led: Array.from(d.led),
      us: Array.from(d.us),
    };
  });
}

/** The records of a job planned as the Mega plans it, step by step in the order `JOB:` counts them. */
export function dosePlanOf(job: PrintJob, planned: JobPlan): DosePlan {
  const { cols, rows } = job.grid;
  const { plan, scan, mixed } = planned;
  if (mixed) {
    const steps: PlannedRecord[][] = [];
    for (const p of mixed.passes) {
      if (p.scan) steps.push(passRecords(job, p.pass));
      else for (const [hx, hy, ...us] of p.stops) steps.push([stopRecord(job, hx, hy, us)]);
    }
    return { cols, rows, steps, unit: 'step' };
  }
  if (scan) return { cols, rows, steps: scan.passes.map((p) => passRecords(job, p)), unit: 'pass' };
  const steps = Array.from({ length: plan.count }, (_, i) => [stopRecord(job, plan.hx[i], plan.hy[i], plan.durations.subarray(4 * i, 4 * i + 4))]);
  return { cols, rows, steps, unit: 'stop' };
}

/** Plans `job` (its order as it ran) for `machine` and gives its records. */
export function planDoses(job: PrintJob, machine: Machine): DosePlan {
  return dosePlanOf(job, planAnyJob({ header: headerOf(job), cells: job.gridData }, machine));
}
