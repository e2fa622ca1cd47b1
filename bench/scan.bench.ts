// P10: exposure on the move (issue 19) against stop-and-fire and against the two limits of a scan; and
// the time the app's planner (the C++ planner as WebAssembly) takes to make its scan and mixed plans.
import type { JobHeader, StrategyName } from '../app/src/protocol/job-types';
import { durationTables } from '../app/src/planner/dose';
import { mixedPassCount, type MixedPlan, type ScanPlan } from '../app/src/planner/plan';
import { moveTimeUs, orderEstimates, planJob, planMixed, planScan } from '../app/src/planner/planner-wasm';
import { compare, type Row } from './harness';
import { BENCH_MACHINE, GEOMETRY } from './planner.bench';
import { boardMask, fillMask, photoMask, sparseMask, textMask, type Mask } from './masks';

export interface P10Row {
  mask: string;
  scan: ScanPlan;
  /** The scan's estimate crossing every blank stretch at the pass's speed (planScan's neverFly). */
  crossingUs: number;
  /** The better of serpentine and shortest stop-and-fire. */
  stops: number;
  /** Mixed mode (issue 28 §1): each band of 8 passes as one group of stops, or pass by pass on the move or stop by stop, whichever is cheaper. */
  mixed: MixedPlan;
  /** Σ dose ÷ 4: four LEDs lit all the time. */
  lightLimit: number;
  /** The passes' lengths at the X axis's maximum speed. */
  travelLimit: number;
  /**
   * What no scan of these passes can beat on this machine: every lit window at the pass's speed,
   * every blank stretch at the axis's maximum speed with no time to speed up or slow down, and each
   * pass's speeding up from rest and slowing down to it (X reverses between passes), with no move,
   * settle or overhead.
   */
  floor: number;
  /** The same with each blank stretch crossed as fast as the X axis's acceleration allows. */
  accel: number;
  /**
   * What the lit windows alone take with any passes at all, the planner's or others that overlap
   * and share out a row's cells: in each column, the cheapest way to cover its lit cells with runs
   * of four consecutive rows (a pass's LEDs, adjacent rows), each run one window as long as its
   * longest on-time and no shorter than crossing a cell at vmax.
   */
  anyPasses: number;
}

function header(mask: Mask, strategy: StrategyName, map: 'linear' | 'threshold'): JobHeader {
  return {
    cols: mask.cols, rows: mask.rows, pitchUm: [50, 50], originUm: [10000, 10000], map, level: 128, fullUs: 2000,
    gainPermille: [1000, 1000, 1000, 1000], thermal: [0, 250], offsets: GEOMETRY['adjacent rows'], strategy, seed: 7,
  };
}

export function p10(): P10Row[] {
  const masks: [Mask, 'linear' | 'threshold'][] = [
    [boardMask(800, 400), 'threshold'],
    [sparseMask(800, 400), 'threshold'],
    [fillMask(200, 200), 'threshold'],
    [photoMask(300, 200), 'linear'],
    [textMask(800, 400), 'threshold'],
  ];
  return masks.map(([mask, map]) => {
    const cells = mask.cells;
    const h = header(mask, 'serpentine', map);
    const stops = Math.min(...(['serpentine', 'shortest'] as StrategyName[]).map((s) => planJob({ header: header(mask, s, map), cells }, BENCH_MACHINE).estimateUs));
    const scan = planScan({ header: h, cells }, BENCH_MACHINE);
    const mixed = planMixed({ header: header(mask, 'mixed', map), cells }, BENCH_MACHINE);
    const crossing = planScan({ header: h, cells }, BENCH_MACHINE, { neverFly: true });
    const table = durationTables(h)[0];
    let dose = 0;
    for (const row of cells) for (let c = 0; c < row.length; c++) dose += table[row[c]];
    const travelLimit = scan.passes.reduce((t, p) => t + ((p.last - p.first + 1) * h.pitchUm[0] * 1e6) / BENCH_MACHINE.vmaxUmS[0], 0);
    return { mask: mask.name, scan, crossingUs: crossing.estimateUs, stops, mixed, lightLimit: dose / 4, travelLimit, ...floorsUs(crossing, h.pitchUm[0]), anyPasses: anyPassesUs(cells, table, h) };
  });
}

/**
 * P10's floors of a plan made without flying (so window j of a pass starts at j × W): each blank
 * stretch at vmax with no time to speed up (`floor`), or in the least time the X axis's
 * acceleration allows, min(g × W, F(g)) of planner.md "Blank stretches" with no threshold or cap
 * (`accel`).
 */
function floorsUs(plan: ScanPlan, pitchUm: number): { floor: number; accel: number } {
  const W = plan.windowUs, blankUs = Math.min(W, (pitchUm * 1e6) / BENCH_MACHINE.vmaxUmS[0]);
  const fly = (g: number) => Math.max(1, moveTimeUs(g * pitchUm + 2 * plan.overscanUm, BENCH_MACHINE.vmaxUmS[0], BENCH_MACHINE.accelUmS2[0]) - 2 * plan.accelUs);
  let floor = 0, accel = 0;
  for (const p of plan.passes) {
    const lit = new Set<number>();
    for (const led of p.leds) for (const [on, off] of led) for (let j = Math.floor(on / W); j * W < off; j++) lit.add(j);
    const windows = p.last - p.first + 1;
    floor += 2 * plan.accelUs + lit.size * W + (windows - lit.size) * blankUs;
    accel += 2 * plan.accelUs + lit.size * W;
    for (let j = 0, prev = -1; j < windows; j++) {
      if (!lit.has(j)) continue;
      const g = j - prev - 1;
      if (prev >= 0 && g > 0) accel += Math.min(g * W, fly(g));
      prev = j;
    }
  }
  return { floor, accel };
}

/** P10's bound on the lit windows of any passes, for the adjacent-rows head (the LEDs on rows hy … hy + 3). */
function anyPassesUs(cells: ArrayLike<number>[], table: Uint32Array, h: JobHeader): number {
  if (h.offsets.some((o, k) => o[0] !== 0 || o[1] !== k)) throw new Error('P10 bounds passes for the adjacent-rows head only');
  const shortest = Math.ceil((h.pitchUm[0] * 1e6) / BENCH_MACHINE.vmaxUmS[0]);
  const rows = cells.length, cols = rows ? cells[0].length : 0;
  const best = new Float64Array(rows + 1); // best[i]: the cheapest cover of the column's lit cells above row i
  let us = 0;
  for (let c = 0; c < cols; c++) {
    for (let i = 0; i < rows; i++) {
      const t = table[cells[i][c]];
      if (t === 0) {
        best[i + 1] = best[i];
        continue;
      }
      // Row i ends a run of one to four rows j … i, as long as its longest on-time.
      best[i + 1] = Infinity;
      for (let j = i, longest = 0; j >= 0 && j > i - 4; j--) {
        longest = Math.max(longest, table[cells[j][c]]);
        best[i + 1] = Math.min(best[i + 1], best[j] + Math.max(longest, shortest));
      }
    }
    us += best[rows];
  }
  return us;
}

/**
 * P10's mixed line (issue 28 §1): the per-band and per-pass choice against stop-and-fire (goal >= 1.00x
 * on every mask) and against the better of the two pure modes (goal on the sparse mask: within 5 %, or better).
 */
function printMixed(rows: P10Row[]): void {
  for (const r of rows) {
    const m = r.mixed.estimateUs, best = Math.min(r.scan.estimateUs, r.stops);
    const scans = r.mixed.passes.filter((p) => p.scan).length, bands = r.mixed.passes.filter((p) => !p.scan && p.band);
    const inBands = bands.reduce((n, p) => n + (!p.scan && p.band ? p.band : 0), 0);
    console.log(
      `P10 ${r.mask.padEnd(7)} mixed ${(m / 1e6).toFixed(1).padStart(6)} s (${scans} of ${mixedPassCount(r.mixed)} passes on the move, ${inBands} in ${bands.length} bands of stops, the rest stop by stop)` +
        `  speed-up ${(r.stops / m).toFixed(2)}x stop-and-fire (goal >= 1.00x), ${(r.scan.estimateUs / m).toFixed(2)}x scan;` +
        `  ${(m / best).toFixed(3)}x the better pure mode (${r.scan.estimateUs <= r.stops ? 'scan' : 'stop-and-fire'}; sparse goal <= 1.050x)`,
    );
  }
}

/** P10's automatic line: the Order list's default, the fastest of every order for the job (job-plan.ts fastestOrder), against stop-and-fire. */
/** The order the automatic choice takes for a mask (the fastest), and its estimate. */
function chosen(r: P10Row): [string, number] {
  const choices: [string, number][] = [['scan', r.scan.estimateUs], ['mixed', r.mixed.estimateUs], ['stop-and-fire', r.stops]];
  return choices.reduce((a, b) => (b[1] < a[1] ? b : a));
}

function printAutomatic(rows: P10Row[]): void {
  for (const r of rows) {
    const [order, fast] = chosen(r);
    console.log(`P10 ${r.mask.padEnd(7)} automatic ${(fast / 1e6).toFixed(1).padStart(6)} s in ${order.padEnd(13)}  speed-up ${(r.stops / fast).toFixed(2)}x  (goal >= 1.00x; the fastest order, by construction)`);
  }
}

export function printP10(rows: P10Row[]): void {
  console.log(`\nP10 scan (exposure on the move) vs stop-and-fire (goal: pcb >= 5x) and vs the larger limit (goal: pcb <= 1.3x); the printhead link at ${BENCH_MACHINE.linkBaud} baud`);
  console.log('  adjacent rows; scan, stop-and-fire, light limit (dose/4), travel limit (passes at vmax); window, passes');
  console.log('  floor: every lit window at the pass speed, every blank one at vmax with no ramp, and each pass speeding up from rest and back; no scan of these passes beats it');
  console.log('  at the axis\'s acceleration: the floor with each blank stretch crossed as fast as the X axis can speed up and slow down');
  console.log('  any passes: the lit windows alone of any passes at all (runs of four rows covering each column\'s lit cells at their longest on-time)');
  const s = (us: number) => `${(us / 1e6).toFixed(1)} s`;
  for (const r of rows) {
    const limit = Math.max(r.lightLimit, r.travelLimit);
    console.log(
      `P10 ${r.mask.padEnd(7)} scan ${s(r.scan.estimateUs).padStart(8)}  stop-and-fire ${s(r.stops).padStart(8)}  light ${s(r.lightLimit).padStart(7)}  travel ${s(r.travelLimit).padStart(7)}` +
        `  speed-up ${(r.stops / r.scan.estimateUs).toFixed(2)}x  /limit ${(r.scan.estimateUs / limit).toFixed(2)}x  (floor ${s(r.floor)}, ${(r.floor / limit).toFixed(2)}x the limit; at the axis's acceleration ${s(r.accel)}, ${(r.accel / limit).toFixed(2)}x; any passes ${s(r.anyPasses)}, ${(r.anyPasses / limit).toFixed(2)}x)` +
        `  (window ${r.scan.windowUs} us, ${r.scan.passes.length} passes; crossing blank stretches at the pass's speed instead: ${s(r.crossingUs)}, speed-up ${(r.stops / r.crossingUs).toFixed(2)}x)`,
    );
  }
  printMixed(rows);
  printAutomatic(rows);
  printTurnArounds(rows);
}

/**
 * P10's turn-arounds (issue 39 §2): where the scan plan's time goes beyond its passes' lit and blank
 * windows and their speeding up (2 × tA, the floor's own): the step engine's moves between passes
 * (the Y hop and the X step from one stroke's end to the next's start, from rest to rest), the
 * Mega's load and the Nano's closing Q of each pass, and what the strokes take beyond the floor's
 * passes (the engine's ramps, the G lead, the steps either side; a pass the link cap slowed).
 */
function printTurnArounds(rows: P10Row[]): void {
  const s = (us: number) => `${(us / 1e6).toFixed(2)} s`;
  for (const r of rows) {
    const [order, fast] = chosen(r);
    const n = r.scan.passes.length;
    const moves = r.scan.passes.reduce((t, p) => t + p.moveUs, 0), ends = r.scan.passes.reduce((t, p) => t + p.wallUs - p.moveUs - p.strokeUs, 0);
    const strokes = r.scan.estimateUs - r.accel - moves - ends;  // the strokes beyond the floor's passes
    console.log(
      `P10 ${r.mask.padEnd(7)} beyond its windows: moves between passes ${s(moves)} (${(moves / Math.max(1, n) / 1000).toFixed(1)} ms a pass), pass load and end ${s(ends)}, strokes past the floor's passes ${s(strokes)}; ` +
        `the scan ${(r.scan.estimateUs / r.accel).toFixed(3)}x its floor at the axis's acceleration; the chosen plan (${order}) ${(fast / r.accel).toFixed(3)}x (goal <= 1.05x), the printhead link at ${BENCH_MACHINE.linkBaud} baud`,
    );
  }
}

/** Bytes a second the printhead link carries at the bench machine's speed (the board's), 10 bits a byte. */
const LINK_BYTES_S = BENCH_MACHINE.linkBaud / 10;

/** A plan's load on the printhead link, as the Mega's M29 counts it: its worst pass and the whole job. Each pass's chain bytes are its link check's (ScanPlanner::chainBytes). */
function linkLoad(plan: ScanPlan): { worst: number; whole: number; events: number; bytes: number } {
  let worst = 0, bytes = 0, busyUs = 0, events = 0;
  for (const p of plan.passes) {
    if (!p.events.length) continue;
    // What the first two programs take is loaded during the move to the run-up.
    const passUs = Math.max(1, p.events[p.events.length - 1][0]);
    worst = Math.max(worst, ((p.chainBytes - p.chainAheadBytes) / LINK_BYTES_S) * 1e6 / passUs);
    bytes += p.chainBytes;
    busyUs += passUs;
    events += p.events.length;
  }
  return { worst, whole: (bytes / LINK_BYTES_S) * 1e6 / Math.max(1, busyUs), events, bytes };
}

/**
 * P11: how hard each scan job works the printhead link. A pass's programs (nano.md "Scan
 * programs") must cross the link (at the board's speed, BENCH_MACHINE.linkBaud) no slower than the pass plays them, less the two
 * loaded before it starts; above 1.00x the chain would underrun. The planner slows a pass until
 * they fit in four fifths of its time, and each program after the first two in four fifths of what
 * the one before it plays less the Mega's relay (planner.md "The printhead link"), so no pass is
 * above 0.80x, and a dense pass is well below it.
 */
export function printP11(rows: P10Row[]): void {
  console.log(
    `\nP11 printhead link load of scan passes (program bytes, the packed B lines and K lines the Mega sends, against ${BENCH_MACHINE.linkBaud} baud over the pass time; the Mega's relay and time to make an event as scan_program.h gives them (kProgramRelayUs, kProgramEventUs); goal: worst pass <= 1.00x, the photo >= 3x faster than stop and fire)`,
  );
  const s = (us: number) => `${(us / 1e6).toFixed(1)} s`;
  for (const r of rows) {
    const now = linkLoad(r.scan);
    const slowed = r.scan.passes.filter((p) => p.windowUs > r.scan.windowUs);
    const widest = Math.max(r.scan.windowUs, ...r.scan.passes.map((p) => p.windowUs));
    console.log(
      `P11 ${r.mask.padEnd(7)} worst pass ${now.worst.toFixed(2)}x  whole job ${now.whole.toFixed(2)}x` +
        `  (${now.events} events, ${(now.bytes / 1024).toFixed(0)} KiB of program lines; ${now.bytes && now.events ? (now.bytes / now.events).toFixed(1) : '0'} B an event)` +
        `  ${slowed.length} of ${r.scan.passes.length} passes slowed for the link (widest window ${widest} us), scan ${s(r.scan.estimateUs)}, ${(r.stops / r.scan.estimateUs).toFixed(2)}x stop-and-fire`,
    );
  }
}

/**
 * P10's scan and mixed plans of three masks by the app's planner (the C++ planner as WebAssembly), and
 * every order weighed as the preview and the dry run weigh them, against one pass summing every cell
 * (each group's baseline, as P7's). planner.md "Speed" has the TypeScript planner's last figures.
 */
export function p10Planning(): Row[] {
  const masks: [Mask, 'linear' | 'threshold'][] = [[boardMask(800, 400), 'threshold'], [sparseMask(800, 400), 'threshold'], [photoMask(300, 200), 'linear']];
  let sink = 0;
  return masks.flatMap(([mask, map]) => {
    const cells = mask.cells;
    const scan = { header: header(mask, 'scan', map), cells }, mixed = { header: header(mask, 'mixed', map), cells };
    return compare(`P10 ${mask.name} ${mask.cols}×${mask.rows}: the app's planner (the C++ planner as WebAssembly, cells in, plan decoded)`, {
      name: 'baseline: one pass summing every cell', run: () => {
        for (const row of cells) for (let i = 0; i < row.length; i++) sink += row[i];
      },
    }, [
      { name: 'planScan', run: () => (sink += planScan(scan, BENCH_MACHINE).estimateUs) },
      { name: 'planMixed', run: () => (sink += planMixed(mixed, BENCH_MACHINE).estimateUs) },
      { name: 'six orders weighed', run: () => (sink += orderEstimates(scan, BENCH_MACHINE).scan) },
    ], 5);
  });
}
