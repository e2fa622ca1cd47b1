// The exposure planner (protocol/planner.md): a job's cells to an ordered list of stops and a time estimate.

import type { JobHeader } from '../protocol/job-types';
import { durationTables } from './dose';
import { MoveTimes, type Machine } from './time-model';

export interface PlannerJob {
  header: JobHeader;
  /** rows arrays of cols values 0-255. */
  cells: ArrayLike<number>[];
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

export function planJob(job: PlannerJob, machine: Machine): Plan {
  const h = job.header;
  const rows = job.cells;
  const tables = durationTables(h);
  const dx = h.offsets.map((o) => o[0]);
  const dy = h.offsets.map((o) => o[1]);
  const dyMin = Math.min(...dy);
  const covered = new Uint8Array(h.rows);
  const out = new StopBuffer();
  const rng = { x: h.seed === 0 ? 0x9e3779b9 : h.seed >>> 0 };
  const moves = new MoveTimes(machine);
  let curX = machine.startUm[0];
  let curY = machine.startUm[1];
  let estimate = 0;
  let travelX = 0;
  let travelY = 0;
  let passes = 0;

  // Per-pass scratch: stop columns and LED values, ascending.
  let passHx = new Int32Array(1024);
  let passVal = new Uint8Array(4096);

  const emit = (hx: number, hy: number, v: Uint8Array, at: number) => {
    const d0 = tables[0][v[at]], d1 = tables[1][v[at + 1]], d2 = tables[2][v[at + 2]], d3 = tables[3][v[at + 3]];
    out.push(hx, hy, d0, d1, d2, d3);
    const x = h.originUm[0] + hx * h.pitchUm[0];
    const y = h.originUm[1] + hy * h.pitchUm[1];
    const mx = Math.abs(x - curX), my = Math.abs(y - curY);
    const move = Math.max(moves.axis(0, mx), moves.axis(1, my));
    estimate += move + (move > 0 ? machine.settleUs : 0) + machine.overheadUs + Math.max(d0, d1, d2, d3);
    travelX += mx;
    travelY += my;
    curX = x;
    curY = y;
  };

  for (let r = 0; r < h.rows; r++) {
    if (covered[r]) continue;
    const row = rows[r];
    let nonEmpty = false;
    for (let c = 0; c < row.length && !nonEmpty; c++) nonEmpty = row[c] > 0;
    if (!nonEmpty) continue;

    const hy = r - dyMin;
    const cols: (Int32Array | null)[] = [null, null, null, null];
    const ledRows = [-1, -1, -1, -1];
    for (let k = 0; k < 4; k++) {
      const rk = hy + dy[k];
      if (rk < 0 || rk >= h.rows || covered[rk]) continue;
      covered[rk] = 1;
      ledRows[k] = rk;
      cols[k] = nonZeroColumns(rows[rk]);
    }

    // Merge the LEDs' head columns ascending into the pass scratch, dropping all-zero stops.
    const idx = [0, 0, 0, 0];
    let n = 0;
    let first = Infinity, last = -Infinity;
    for (let k = 0; k < 4; k++) {
      const ck = cols[k];
      if (ck && ck.length) {
        first = Math.min(first, ck[0] - dx[k]);
        last = Math.max(last, ck[ck.length - 1] - dx[k]);
      }
    }
    for (;;) {
      let best = Infinity;
      for (let k = 0; k < 4; k++) {
        const ck = cols[k];
        if (ck && idx[k] < ck.length) best = Math.min(best, ck[idx[k]] - dx[k]);
      }
      if (best === Infinity) break;
      if (n === passHx.length) {
        const hx2 = new Int32Array(n * 2);
        hx2.set(passHx);
        passHx = hx2;
        const v2 = new Uint8Array(n * 8);
        v2.set(passVal);
        passVal = v2;
      }
      let any = false;
      for (let k = 0; k < 4; k++) {
        const ck = cols[k];
        let v = 0;
        if (ck && idx[k] < ck.length && ck[idx[k]] - dx[k] === best) {
          v = rows[ledRows[k]][ck[idx[k]]];
          idx[k]++;
          if (tables[k][v] > 0) any = true;
        }
        passVal[n * 4 + k] = v;
      }
      if (any) passHx[n++] = best;
    }
    if (n === 0) continue;

    let descending = false;
    if (h.strategy === 'serpentine') descending = passes % 2 === 1;
    else if (h.strategy === 'shortest') {
      const xf = h.originUm[0] + first * h.pitchUm[0];
      const xl = h.originUm[0] + last * h.pitchUm[0];
      descending = Math.abs(xf - curX) > Math.abs(xl - curX);
    }
    passes++;

    if (h.strategy === 'random') {
      const order = new Int32Array(BLOCK);
      for (let start = 0; start < n; start += BLOCK) {
        const len = Math.min(BLOCK, n - start);
        for (let i = 0; i < len; i++) order[i] = start + i;
        for (let i = len - 1; i >= 1; i--) {
          const j = xorshift32(rng) % (i + 1);
          const t = order[i];
          order[i] = order[j];
          order[j] = t;
        }
        for (let i = 0; i < len; i++) emit(passHx[order[i]], hy, passVal, order[i] * 4);
      }
    } else if (descending) {
      for (let i = n - 1; i >= 0; i--) emit(passHx[i], hy, passVal, i * 4);
    } else {
      for (let i = 0; i < n; i++) emit(passHx[i], hy, passVal, i * 4);
    }
  }

  return {
    count: out.count,
    hx: out.hx.subarray(0, out.count),
    hy: out.hy.subarray(0, out.count),
    durations: out.durations.subarray(0, out.count * 4),
    passes,
    estimateUs: estimate,
    travelUm: [travelX, travelY],
  };
}
