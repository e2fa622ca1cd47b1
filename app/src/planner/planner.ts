// The exposure planner (protocol/planner.md): a job's cells to an ordered list of stops and a time estimate.

import type { JobHeader } from '../protocol/job-types';
import { durationTables } from './dose';
import { MoveTimes, type MotionModel } from './time-model';

export interface PlannerJob {
  header: JobHeader;
  /** rows arrays of cols values 0-255. */
  cells: ArrayLike<number>[];
  /**
   * For a job still arriving (stream mode, protocol/mega.md M828): only rows below this have arrived,
   * the rest read as 0. The plan then holds only the stops that no later row can change
   * (protocol/planner.md "Planning while rows arrive"), a prefix of the full job's plan.
   */
  knownRows?: number;
}

export interface Plan {
  count: number;
  hx: Int32Array;
  hy: Int32Array;
  /** 4 per stop, LED 0-3, µs. */
  durations: Uint32Array;
  passes: number;
  estimateUs: number;
  /** Head travel in µm, X and Y. */
  travelUm: [number, number];
}

const BLOCK = 32;

/** Columns with a value above 0, ascending. */
function nonZeroColumns(row: ArrayLike<number>): Int32Array {
  let n = 0;
  for (let c = 0; c < row.length; c++) if (row[c] > 0) n++;
  const out = new Int32Array(n);
  n = 0;
  for (let c = 0; c < row.length; c++) if (row[c] > 0) out[n++] = c;
  return out;
}

function xorshift32(state: { x: number }): number {
  let x = state.x;
  x ^= x << 13;
  x >>>= 0;
  x ^= x >>> 17;
  x ^= x << 5;
  x >>>= 0;
  state.x = x;
  return x;
}

/** Growable stop buffer in typed arrays (a million stops without a million objects). */
class StopBuffer {
  count = 0;
  hx = new Int32Array(1024);
  hy = new Int32Array(1024);
  durations = new Uint32Array(4096);

  push(hx: number, hy: number, d0: number, d1: number, d2: number, d3: number): void {
    if (this.count === this.hx.length) {
      const grow = <T extends Int32Array | Uint32Array>(a: T, n: number): T => {
        const b = new (a.constructor as new (n: number) => T)(n);
        b.set(a);
        return b;
      };
      this.hx = grow(this.hx, this.count * 2);
      this.hy = grow(this.hy, this.count * 2);
      this.durations = grow(this.durations, this.count * 8);
    }
    const i = this.count++;
    this.hx[i] = hx;
    this.hy[i] = hy;
    const d = this.durations;
    d[i * 4] = d0;
    d[i * 4 + 1] = d1;
    d[i * 4 + 2] = d2;
    d[i * 4 + 3] = d3;
  }
}

/** One pass: its head row and its stops ascending by head column, with each LED's cell value. */
interface Pass {
  hy: number;
  n: number;
  hx: Int32Array;
  /** 4 values per stop, LED 0-3 (0 = no cell). */
  val: Uint8Array;
  /** Smallest and largest head column of the pass's non-zero cells. */
  first: number;
  last: number;
}

/** A pass's head row and the row each LED exposes in it, or -1. */
export interface PassRows {
  hy: number;
  ledRows: number[];
}

/** The rows each pass gives its LEDs, in the order the passes open (protocol/planner.md "Passes"). */
export function passRows(h: JobHeader, rows: ArrayLike<number>[]): PassRows[] {
  const dy = h.offsets.map((o) => o[1]);
  const dyMin = Math.min(...dy);
  const covered = new Uint8Array(h.rows);
  const out: PassRows[] = [];
  for (let r = 0; r < h.rows; r++) {
    if (covered[r]) continue;
    const row = rows[r];
    let nonEmpty = false;
    for (let c = 0; c < row.length && !nonEmpty; c++) nonEmpty = row[c] > 0;
    if (!nonEmpty) continue;
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

/** Passes in the order they open (protocol/planner.md "Passes"), stops merged ascending. */
function buildPasses(h: JobHeader, rows: ArrayLike<number>[], tables: Uint32Array[]): Pass[] {
  const dx = h.offsets.map((o) => o[0]);
  const passes: Pass[] = [];
  for (const { hy, ledRows } of passRows(h, rows)) {
    const cols = ledRows.map((rk) => (rk < 0 ? null : nonZeroColumns(rows[rk])));
    let first = Infinity, last = -Infinity, total = 0;
    for (let k = 0; k < 4; k++) {
      const ck = cols[k];
      if (!ck || !ck.length) continue;
      first = Math.min(first, ck[0] - dx[k]);
      last = Math.max(last, ck[ck.length - 1] - dx[k]);
      total += ck.length;
    }
    const hx = new Int32Array(total);
    const val = new Uint8Array(total * 4);
    const idx = [0, 0, 0, 0];
    let n = 0;
    for (;;) {
      let best = Infinity;
      for (let k = 0; k < 4; k++) {
        const ck = cols[k];
        if (ck && idx[k] < ck.length) best = Math.min(best, ck[idx[k]] - dx[k]);
      }
      if (best === Infinity) break;
      let any = false;
      for (let k = 0; k < 4; k++) {
        const ck = cols[k];
        let v = 0;
        if (ck && idx[k] < ck.length && ck[idx[k]] - dx[k] === best) {
          v = rows[ledRows[k]][ck[idx[k]]];
          idx[k]++;
          if (tables[k][v] > 0) any = true;
        }
        val[n * 4 + k] = v;
      }
      if (any) hx[n++] = best; // an all-dark stop is overwritten by the next one
    }
    passes.push({ hy, n, hx, val, first, last });
  }
  return passes;
}

export const SHORTEST_BAND = 8;

export function planJob(job: PlannerJob, machine: MotionModel): Plan {
  const h = job.header;
  const tables = durationTables(h);
  const out = new StopBuffer();
  const rng = { x: h.seed === 0 ? 0x9e3779b9 : h.seed >>> 0 };
  const moves = new MoveTimes(machine);
  const X = (hx: number) => h.originUm[0] + hx * h.pitchUm[0];
  const Y = (hy: number) => h.originUm[1] + hy * h.pitchUm[1];
  let curX = machine.startUm[0];
  let curY = machine.startUm[1];
  let estimate = 0;
  let travelX = 0;
  let travelY = 0;
  let emitted = 0;

  /** The time model's cost of one stop from (x, y); protocol/planner.md "Time model". */
  const stopCost = (x: number, y: number, fromX: number, fromY: number, v: Uint8Array, at: number) =>
    moves.stop(x, y, fromX, fromY, [tables[0][v[at]], tables[1][v[at + 1]], tables[2][v[at + 2]], tables[3][v[at + 3]]]);
  const emit = (hx: number, hy: number, v: Uint8Array, at: number) => {
    out.push(hx, hy, tables[0][v[at]], tables[1][v[at + 1]], tables[2][v[at + 2]], tables[3][v[at + 3]]);
    const x = X(hx), y = Y(hy);
    estimate += stopCost(x, y, curX, curY, v, at);
    travelX += Math.abs(x - curX);
    travelY += Math.abs(y - curY);
    curX = x;
    curY = y;
  };
  /** Ascending unless the pass's far end is nearer to `x`. */
  const nearerEndDescending = (p: Pass, x: number) => Math.abs(X(p.first) - x) > Math.abs(X(p.last) - x);

  const passes = buildPasses(h, job.cells, tables);
  const arrived = job.knownRows ?? h.rows;
  const dyMax = Math.max(...h.offsets.map((o) => o[1]));
  /** A pass is settled once the last row any of its LEDs can read has arrived. */
  const settled = (p: Pass) => arrived >= h.rows || Math.min(p.hy + dyMax, h.rows - 1) < arrived;
  if (h.strategy === 'shortest') {
    for (let b = 0; b < passes.length; b += SHORTEST_BAND) {
      const opened = passes.slice(b, b + SHORTEST_BAND);
      // A band still short of passes may gain one from rows yet to come.
      if (arrived < h.rows && (opened.length < SHORTEST_BAND || !opened.every(settled))) break;
      const band = opened.filter((p) => p.n > 0);
      if (band.length === 0) continue;
      const byRows = rowOrder(band, curX);
      const byColumns = columnOrder(band, curX, curY);
      const cost = (order: [Pass, number][]) => {
        let t = 0, x = curX, y = curY;
        for (const [p, i] of order) {
          const nx = X(p.hx[i]), ny = Y(p.hy);
          t += stopCost(nx, ny, x, y, p.val, i * 4);
          x = nx;
          y = ny;
        }
        return t;
      };
      const order = cost(byColumns) < cost(byRows) ? byColumns : byRows;
      for (const [p, i] of order) emit(p.hx[i], p.hy, p.val, i * 4);
      emitted += band.length;
    }
  } else {
    for (const p of passes) {
      if (!settled(p)) break;
      if (p.n === 0) continue;
      if (h.strategy === 'random') {
        const order = new Int32Array(BLOCK);
        for (let start = 0; start < p.n; start += BLOCK) {
          const len = Math.min(BLOCK, p.n - start);
          for (let i = 0; i < len; i++) order[i] = start + i;
          for (let i = len - 1; i >= 1; i--) {
            const j = xorshift32(rng) % (i + 1);
            const t = order[i];
            order[i] = order[j];
            order[j] = t;
          }
          for (let i = 0; i < len; i++) emit(p.hx[order[i]], p.hy, p.val, order[i] * 4);
        }
      } else if (h.strategy === 'serpentine' && emitted % 2 === 1) {
        for (let i = p.n - 1; i >= 0; i--) emit(p.hx[i], p.hy, p.val, i * 4);
      } else {
        for (let i = 0; i < p.n; i++) emit(p.hx[i], p.hy, p.val, i * 4);
      }
      emitted++;
    }
  }

  /** Band order A: pass after pass, each from its nearer end. */
  function rowOrder(band: Pass[], startX: number): [Pass, number][] {
    const order: [Pass, number][] = [];
    let x = startX;
    for (const p of band) {
      const desc = nearerEndDescending(p, x);
      for (let j = 0; j < p.n; j++) order.push([p, desc ? p.n - 1 - j : j]);
      x = X(p.hx[desc ? 0 : p.n - 1]);
    }
    return order;
  }

  /** Band order B: column after column across the band's passes, each column from its nearer end in Y. */
  function columnOrder(band: Pass[], startX: number, startY: number): [Pass, number][] {
    const first = Math.min(...band.map((p) => p.first));
    const last = Math.max(...band.map((p) => p.last));
    const desc = Math.abs(X(first) - startX) > Math.abs(X(last) - startX);
    const idx = band.map((p) => (desc ? p.n - 1 : 0));
    const order: [Pass, number][] = [];
    let y = startY;
    const column: number[] = [];
    for (;;) {
      let best = desc ? -Infinity : Infinity;
      band.forEach((p, q) => {
        const i = idx[q];
        if (i < 0 || i >= p.n) return;
        best = desc ? Math.max(best, p.hx[i]) : Math.min(best, p.hx[i]);
      });
      if (!Number.isFinite(best)) break;
      column.length = 0;
      band.forEach((p, q) => {
        const i = idx[q];
        if (i >= 0 && i < p.n && p.hx[i] === best) {
          column.push(q);
          idx[q] += desc ? -1 : 1;
        }
      }); // passes are in ascending hy, so the column is too
      const up = Math.abs(Y(band[column[0]].hy) - y) > Math.abs(Y(band[column[column.length - 1]].hy) - y);
      if (up) column.reverse();
      for (const q of column) order.push([band[q], idx[q] - (desc ? -1 : 1)]);
      y = Y(band[column[column.length - 1]].hy);
    }
    return order;
  }

  return {
    count: out.count,
    hx: out.hx.subarray(0, out.count),
    hy: out.hy.subarray(0, out.count),
    durations: out.durations.subarray(0, out.count * 4),
    passes: emitted,
    estimateUs: estimate,
    travelUm: [travelX, travelY],
  };
}
