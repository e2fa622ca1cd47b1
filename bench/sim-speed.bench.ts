// The simulated printer's speed (issue 27): the firmware's own C++ as WebAssembly, with its physics,
// running two jobs end to end on this machine, in seconds of the printer's time per second of wall
// time. The baseline is real time (1x): the TypeScript printer it replaced is gone. The goal: the P10
// pcb scan job at 20x or faster. And the module's size, gzipped, which the app loads on demand.
import { readFileSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import '../app/src/sim/wasm/node-firmware';
import { encodeJob } from '../app/src/protocol/job-encode';
import type { PrintJob } from '../app/src/protocol/job-types';
import { SimHost } from '../app/src/sim/sim-host.fixture';
import { FIRMWARE_FILE } from '../app/src/sim/wasm/node-firmware';
import { boardMask } from './masks';

function job(name: string, cols: number, rows: number, cells: number[][] | Uint8Array[], strategy: 'serpentine' | 'scan', fullUs: number): PrintJob {
  return {
    name, grid: { cols, rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 10000, y: 10000 },
    dose: { map: 'threshold', level: 128, fullUs }, leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: strategy }, gridData: cells.map((r) => Array.from(r)),
  };
}

/** Runs `j` from M24 (paced: it waits for the head to cool) for at most `maxS` of the printer's time; its speed over real time. */
function speedOf(j: PrintJob, maxS: number, paced: boolean): { ratio: number; simS: number; wallS: number; end: string } {
  const h = new SimHost();
  h.cmd('G28');
  h.upload('B.UVJ', encodeJob(j));
  h.cmd('M23 B.UVJ');
  const t0 = performance.now();
  const c0 = h.sim.clock.now;
  h.cmd(paced ? 'M24 P1' : 'M24');
  let end = 'JOB:running';
  try {
    end = h.waitFor(/^JOB:(done|paused|aborted|failed)/, maxS * 1000);
  } catch {
    /* ran its share of the time */
  }
  const wallS = (performance.now() - t0) / 1000;
  const simS = (h.sim.clock.now - c0) / 1e6;
  return { ratio: simS / wallS, simS, wallS, end: end.split(' ')[0] };
}

export function simSpeed(): void {
  console.log("\nS1 the simulated printer's speed: the firmware's C++ as WebAssembly, in printer seconds per wall second (baseline: real time, 1x; goal: the pcb scan job >= 20x)");
  const fill = Array.from({ length: 400 }, () => new Uint8Array(600).fill(255));
  const board = boardMask(800, 400);
  const cases: [string, PrintJob, number, boolean][] = [
    ['30 x 20 mm filled board, stop and fire, 40 ms, paced', job('stops', 600, 400, fill, 'serpentine', 40_000), 120, true],
    ['P10 pcb mask 40 x 20 mm, scan (on the move)', job('pcb', board.cols, board.rows, board.cells, 'scan', 2000), 240, false],
  ];
  for (const [name, j, maxS, paced] of cases) {
    const r = speedOf(j, maxS, paced);
    console.log(`  ${name.padEnd(54)} ${r.ratio.toFixed(0).padStart(5)}x   (${r.simS.toFixed(0)} s of the printer's time in ${r.wallS.toFixed(1)} s; ${r.end})`);
  }
  const bytes = readFileSync(FIRMWARE_FILE);
  console.log(`  the module, printer.wasm: ${(bytes.length / 1024).toFixed(1)} KB, ${(gzipSync(bytes, { level: 9 }).length / 1024).toFixed(1)} KB gzipped (loaded on demand: not in the first load, not in the ESP's image)`);
}
