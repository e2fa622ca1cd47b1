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
  since(from: number): { stops: number[]; lines: number; clears: number };
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

/** The map as the page shows it: its words, counted in the work worker, and its pixels binned there (work/dose-work.ts). */
export type DoseMapView = Omit<DeliveredMap, 'state' | 'twice' | 'plannedUs' | 'deliveredUs'> & {
  image: { width: number; height: number; zoom: number; pixels: Uint32Array<ArrayBuffer> };
};

/** What the map's words are made of. */
type MapWords = Pick<DeliveredMap, 'counts' | 'twiceSteps' | 'cutSteps' | 'unit' | 'steps'>;

/**
 * The map of what a ledger reported against a plan, kept up to date as reports come: each update
 * counts again only the steps whose lines changed, so a whole bed's map follows its job without
 * holding the page (a million cells counted afresh took 170 ms).
 */
export class DoseTally {
  readonly #plan: DosePlan;
  /** The ledger's lines counted so far, and the steps they reported; those lit twice, those cut. */
  #lines = 0;
  #clears = -1;
  readonly #counted = new Set<number>();
  readonly #twice = new Set<number>();
  readonly #cut = new Set<number>();
  /** The part of its plan each record's LED gave, as last counted; NaN: not reported. */
  readonly #part: Float64Array;
  /** Per cell: how many of its planned lights have no report. */
  readonly #unknown: Uint32Array;
  readonly #map: DeliveredMap;
  /** What the last update gave. */
  #last: DeliveredMap;

  constructor(plan: DosePlan) {
    this.#plan = plan;
    const n = plan.cols * plan.rows;
    this.#part = new Float64Array(plan.ledUs.length).fill(NaN);
    this.#unknown = new Uint32Array(n);
    const plannedUs = new Float32Array(n); // 7 figures: ample for 2 %, half the memory of a whole bed
    for (let e = 0; e < plan.cell.length; e++) (plannedUs[plan.cell[e]] += plan.us[e]), this.#unknown[plan.cell[e]]++;
    const state = new Uint8Array(n);
    let waiting = 0;
    for (let c = 0; c < n; c++) if (plannedUs[c] > 0) (state[c] = CellDose.Waiting), waiting++;
    this.#map = {
      cols: plan.cols, rows: plan.rows, state, twice: new Uint8Array(n), plannedUs, deliveredUs: new Float32Array(n),
      counts: { within: 0, off: 0, dark: 0, waiting, twice: 0 }, twiceSteps: [], cutSteps: [], worst: 0, unit: plan.unit, steps: plan.steps,
    };
    this.#last = this.#map;
  }

  /** Counts what changed in `ledger` since the last update; the map, a new object when anything did. */
  update(ledger: DoseLedgerView): DeliveredMap {
    const p = this.#plan, m = this.#map;
    let { stops, lines, clears } = ledger.since(this.#lines);
    if (clears !== this.#clears) {
      // The ledger was cleared since (another job): the steps counted before are counted again, with its lines from the first.
      ({ stops, lines } = ledger.since(0));
      stops = [...this.#counted, ...stops];
      this.#clears = clears;
      m.worst = 0; // the cells counted before are counted again: their worst with them
    }
    this.#lines = lines;
    const touched: number[] = [];
    for (const step of new Set(stops)) {
      if (step >= p.steps) continue; // past the plan: the view says so
      const s = ledger.stop(step);
      if (s) this.#counted.add(step);
      else this.#counted.delete(step);
      if (s?.twice) this.#twice.add(step);
      else this.#twice.delete(step);
      if (s?.cutUs.length) this.#cut.add(step);
      else this.#cut.delete(step);
      for (let r = p.firstRecord[step]; r < p.firstRecord[step + 1]; r++) {
        const on = s?.programs.get(r - p.firstRecord[step]);
        for (let k = 0; k < 4; k++) {
          const was = this.#part[4 * r + k];
          const now = !on ? NaN : p.ledUs[4 * r + k] > 0 ? on[k] / p.ledUs[4 * r + k] : 0;
          if (Object.is(was, now)) continue;
          this.#part[4 * r + k] = now;
          for (let e = p.firstEntry[r]; e < p.firstEntry[r + 1]; e++) {
            if (p.led[e] !== k) continue;
            const c = p.cell[e];
            if (Number.isNaN(was)) this.#unknown[c]--;
            else m.deliveredUs[c] -= p.us[e] * was;
            if (Number.isNaN(now)) this.#unknown[c]++;
            else m.deliveredUs[c] += p.us[e] * now;
            touched.push(c);
          }
        }
        const twice = s?.twice ? 1 : 0;
        for (let e = p.firstEntry[r]; e < p.firstEntry[r + 1]; e++) {
          const c = p.cell[e];
          if (m.twice[c] !== twice) (m.counts.twice += twice ? 1 : -1), (m.twice[c] = twice);
        }
      }
    }
    if (!stops.length) return this.#last;
    for (const c of touched) this.#recount(c);
    const sorted = (set: Set<number>) => [...set].sort((a, b) => a - b);
    return (this.#last = { ...m, twiceSteps: sorted(this.#twice), cutSteps: sorted(this.#cut), counts: { ...m.counts } });
  }

  /** A cell's state again, from its light so far. */
  #recount(c: number): void {
    const m = this.#map, counts = m.counts;
    const before = m.state[c];
    let after: number = CellDose.Waiting;
    if (this.#unknown[c] === 0) {
      const part = Math.abs(m.deliveredUs[c] / m.plannedUs[c] - 1);
      if (m.deliveredUs[c] <= m.plannedUs[c] * 1e-6) after = CellDose.Dark;
      else {
        m.worst = Math.max(m.worst, part);
        after = part > DOSE_TOLERANCE ? CellDose.Off : CellDose.Within;
      }
    }
    if (after === before) return;
    const key = ['', 'within', 'off', 'dark', 'waiting'] as const;
    counts[key[before] as 'within']--;
    counts[key[after] as 'within']++;
    m.state[c] = after;
  }
}

/** The map of what `ledger` reported against `plan`, counted afresh. */
export function deliveredMap(plan: DosePlan, ledger: DoseLedgerView): DeliveredMap {
  return new DoseTally(plan).update(ledger);
}

/** 12480 as "12 480" (a thin space between groups of three, as SI writes numbers). */
export function grouped(n: number): string {
  return String(n).replace(/\B(?=(\d{3})+(?!\d))/g, '\u202f');
}

const plural = (n: number, one: string, many = `${one}s`) => `${grouped(n)} ${n === 1 ? one : many}`;
const unitName = (m: MapWords, n: number) => (m.unit === 'pass' ? (n === 1 ? 'pass' : 'passes') : n === 1 ? m.unit : `${m.unit}s`);

/** What the cells whose records have not come are called: while the job runs, "not reported yet". */
export const waitingWords = (ended: boolean): string => (ended ? 'not reported to this page' : 'not reported yet');

/**
 * The map in one line: "12 480 cells within 2 %, 0 off, 0 never lit, 3 stops lit twice by a resume".
 * `ended`: the job has ended, so a record still missing will not come (lit while no page listened, or lost).
 */
export function doseSummary(m: MapWords, ended = false): string {
  const parts = [`${plural(m.counts.within, 'cell')} within ${DOSE_TOLERANCE * 100} %`, `${grouped(m.counts.off)} off`, `${grouped(m.counts.dark)} never lit`];
  if (m.counts.waiting) parts.push(`${grouped(m.counts.waiting)} ${waitingWords(ended)}`);
  parts.push(`${grouped(m.twiceSteps.length)} ${unitName(m, m.twiceSteps.length)} lit twice by a resume`);
  return parts.join(', ');
}

/** The steps a fault or a restart cut, named as the job panel counts them (from 1, "of" the job's). */
export function faultedWords(m: MapWords): string | null {
  if (!m.cutSteps.length) return null;
  const names = m.cutSteps.map((s) => `${m.unit} ${s + 1} of ${m.steps}`);
  const list = names.length === 1 ? names[0] : `${names.slice(0, -1).join(', ')} and ${names[names.length - 1]}`;
  const again = m.cutSteps.every((s) => m.twiceSteps.includes(s));
  return `${list[0].toUpperCase()}${list.slice(1)}: cut short by a fault or a restart${again ? ', then exposed again from its start; its cells are counted once, from the whole exposure' : ', and not exposed again yet'}.`;
}
