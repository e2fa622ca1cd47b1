// Each cell's delivered dose against its planned dose, from a job's records (dose-plan.ts) and what the
// head reported (device/dose-ledger.ts): a record's LED gives each of its cells the part of the planned
// light it gave in all (the Nano times a record per LED, not per cell). A cell is counted once, from
// the records without `cut`; cells of a stop a cut or a resume lit twice are marked.

import type { StopDose } from '../device/dose-ledger';
import type { DosePlan } from './dose-plan';

/** How far a cell's dose may be from its plan and still count as given. */
export const DOSE_TOLERANCE = 0.02;

/** A cell's state on the map: no light planned; within 2 % of its plan; more than 2 % off; its records
 *  came and it got no light; a record of its light has not come (the head is not there yet, or the Nano lost it). */
export const CellDose = { None: 0, Within: 1, Off: 2, Dark: 3, Waiting: 4 } as const;

export interface DoseLedgerView {
  stop(n: number): StopDose | undefined;
}

export interface DeliveredMap {
  cols: number;
  rows: number;
  /** CellDose per cell, row × cols + col. */
  state: Uint8Array;
  /** 1 where the cell's stop was lit twice (a cut, then the stop again). */
  twice: Uint8Array;
  plannedUs: Float32Array;
  deliveredUs: Float32Array;
  counts: { within: number; off: number; dark: number; waiting: number; twice: number };
  /** Steps (from 0, as JOB: counts them) lit twice, and those whose light was cut (the faulted ones). */
  twiceSteps: number[];
  cutSteps: number[];
  /** The largest part off among the cells counted, e.g. 0.004 for 0.4 %. */
  worst: number;
  unit: DosePlan['unit'];
  steps: number;
}

/** The map of what `ledger` reported against `plan`. */
export function deliveredMap(plan: DosePlan, ledger: DoseLedgerView): DeliveredMap {
  const { cols, rows } = plan;
  const n = cols * rows;
  const plannedUs = new Float32Array(n), deliveredUs = new Float32Array(n); // 7 figures: ample for 2 %, half the memory of a whole bed
  const unknown = new Uint8Array(n), twice = new Uint8Array(n);
  const twiceSteps: number[] = [], cutSteps: number[] = [];
  plan.steps.forEach((records, step) => {
    const s = ledger.stop(step);
    if (s?.twice) twiceSteps.push(step);
    if (s?.cutUs.length) cutSteps.push(step);
    records.forEach((r, program) => {
      const on = s?.programs.get(program);
      for (let i = 0; i < r.cell.length; i++) {
        const c = r.cell[i], k = r.led[i];
        plannedUs[c] += r.us[i];
        if (s?.twice) twice[c] = 1;
        if (!on) unknown[c] = 1;
        else if (r.ledUs[k] > 0) deliveredUs[c] += (r.us[i] * on[k]) / r.ledUs[k];
      }
    });
  });
  const state = new Uint8Array(n);
  const counts = { within: 0, off: 0, dark: 0, waiting: 0, twice: 0 };
  let worst = 0;
  for (let c = 0; c < n; c++) {
    if (plannedUs[c] <= 0) continue;
    if (twice[c]) counts.twice++;
    if (unknown[c]) (state[c] = CellDose.Waiting), counts.waiting++;
    else if (deliveredUs[c] <= 0) (state[c] = CellDose.Dark), counts.dark++;
    else {
      const part = Math.abs(deliveredUs[c] / plannedUs[c] - 1);
      worst = Math.max(worst, part);
      if (part > DOSE_TOLERANCE) (state[c] = CellDose.Off), counts.off++;
      else (state[c] = CellDose.Within), counts.within++;
    }
  }
  return { cols, rows, state, twice, plannedUs, deliveredUs, counts, twiceSteps, cutSteps, worst, unit: plan.unit, steps: plan.steps.length };
}

/** 12480 as "12 480" (a thin space between groups of three, as SI writes numbers). */
export function grouped(n: number): string {
  return String(n).replace(/\B(?=(\d{3})+(?!\d))/g, '\u202f');
}

const plural = (n: number, one: string, many = `${one}s`) => `${grouped(n)} ${n === 1 ? one : many}`;
const unitName = (m: DeliveredMap, n: number) => (m.unit === 'pass' ? (n === 1 ? 'pass' : 'passes') : n === 1 ? m.unit : `${m.unit}s`);

/** What the cells whose records have not come are called: while the job runs, "not reported yet". */
export const waitingWords = (ended: boolean): string => (ended ? 'not reported to this page' : 'not reported yet');

/**
 * The map in one line: "12 480 cells within 2 %, 0 off, 0 never lit, 3 stops lit twice by a resume".
 * `ended`: the job has ended, so a record still missing will not come (lit while no page listened, or lost).
 */
export function doseSummary(m: DeliveredMap, ended = false): string {
  const parts = [`${plural(m.counts.within, 'cell')} within ${DOSE_TOLERANCE * 100} %`, `${grouped(m.counts.off)} off`, `${grouped(m.counts.dark)} never lit`];
  if (m.counts.waiting) parts.push(`${grouped(m.counts.waiting)} ${waitingWords(ended)}`);
  parts.push(`${grouped(m.twiceSteps.length)} ${unitName(m, m.twiceSteps.length)} lit twice by a resume`);
  return parts.join(', ');
}

/** The steps a fault or a restart cut, named as the job panel counts them (from 1, "of" the job's). */
export function faultedWords(m: DeliveredMap): string | null {
  if (!m.cutSteps.length) return null;
  const names = m.cutSteps.map((s) => `${m.unit} ${s + 1} of ${m.steps}`);
  const list = names.length === 1 ? names[0] : `${names.slice(0, -1).join(', ')} and ${names[names.length - 1]}`;
  const again = m.cutSteps.every((s) => m.twiceSteps.includes(s));
  return `${list[0].toUpperCase()}${list.slice(1)}: cut short by a fault or a restart${again ? ', then exposed again from its start; its cells are counted once, from the whole exposure' : ', and not exposed again yet'}.`;
}
