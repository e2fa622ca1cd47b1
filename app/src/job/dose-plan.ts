// What each dose record of a job should give, and to which cells (protocol/mega.md "Dose reports"):
// a stop's F its cells' durations; a pass on the move, program by program, the light of the events
// the chain gives that program (protocol/nano.md "Scan programs": 64 events a program), cut at the
// program's time 0 and its last event as the Nano counts a record's light.

import { headerOf } from '../planner/job-header';
import { planAnyJob, type JobPlan } from '../planner/job-plan';
import type { ScanPass } from '../planner/plan';
import type { MotionModel } from '../planner/time-model';
import { scanDoses } from '../preview/scan-preview';
import type { PrintJob } from '../protocol/job-types';
import { PROGRAM_EVENTS } from '../protocol/nano';

/** One record's planned light: each LED's on-time, and the cells it falls on (row × cols + col) with their µs. */
export interface PlannedRecord {
  ledUs: number[];
  cell: number[];
  led: number[];
  us: number[];
}

/**
 * A job's records packed in typed arrays (a whole bed's has a million cells), kept in the work worker
 * for as long as the job's map is shown (work/dose-work.ts).
 */
export interface DosePlan {
  cols: number;
  rows: number;
  /** What a step is called to a person: a stop, a pass on the move, or (mixed) either. */
  unit: 'stop' | 'pass' | 'step';
  /** Steps, as `JOB:` counts them. */
  steps: number;
  /** Step s's records are firstRecord[s] … firstRecord[s + 1] − 1, its program p at firstRecord[s] + p. */
  firstRecord: Uint32Array;
  /** Each record's planned on-time per LED, µs, four a record. */
  ledUs: Float64Array;
  /** Record r's cells are entries firstEntry[r] … firstEntry[r + 1] − 1. */
  firstEntry: Uint32Array;
  cell: Uint32Array;
  led: Uint8Array;
  us: Float64Array;
}

/** Packs each step's records (steps[stop][program]). */
export function packDosePlan(cols: number, rows: number, unit: DosePlan['unit'], steps: PlannedRecord[][]): DosePlan {
  const records = steps.flat();
  const entries = records.reduce((n, r) => n + r.cell.length, 0);
  const p: DosePlan = {
    cols, rows, unit, steps: steps.length,
    firstRecord: new Uint32Array(steps.length + 1), ledUs: new Float64Array(4 * records.length), firstEntry: new Uint32Array(records.length + 1),
    cell: new Uint32Array(entries), led: new Uint8Array(entries), us: new Float64Array(entries),
  };
  let r = 0, e = 0;
  steps.forEach((step, s) => {
    p.firstRecord[s] = r;
    for (const rec of step) {
      p.ledUs.set(rec.ledUs, 4 * r);
      p.firstEntry[r++] = e;
      p.cell.set(rec.cell, e), p.led.set(rec.led, e), p.us.set(rec.us, e);
      e += rec.cell.length;
    }
  });
  p.firstRecord[steps.length] = r;
  p.firstEntry[r] = e;
  return p;
}

/** How many programs step s has (1 for a stop). */
export const programCount = (p: DosePlan, s: number): number => p.firstRecord[s + 1] - p.firstRecord[s];

/** Step s's program's record, unpacked. */
export function recordOf(p: DosePlan, s: number, program = 0): PlannedRecord {
  const r = p.firstRecord[s] + program, from = p.firstEntry[r], to = p.firstEntry[r + 1];
  return { ledUs: Array.from(p.ledUs.subarray(4 * r, 4 * r + 4)), cell: Array.from(p.cell.subarray(from, to)), led: Array.from(p.led.subarray(from, to)), us: Array.from(p.us.subarray(from, to)) };
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
    return packDosePlan(cols, rows, 'step', steps);
  }
  if (scan) return packDosePlan(cols, rows, 'pass', scan.passes.map((p) => passRecords(job, p)));
  const steps = Array.from({ length: plan.count }, (_, i) => [stopRecord(job, plan.hx[i], plan.hy[i], plan.durations.subarray(4 * i, 4 * i + 4))]);
  return packDosePlan(cols, rows, 'stop', steps);
}

/** Plans `job` (its order as it ran) for `machine` and gives its records. */
export function planDoses(job: PrintJob, machine: MotionModel): DosePlan {
  return dosePlanOf(job, planAnyJob({ header: headerOf(job), cells: job.gridData }, machine));
}
