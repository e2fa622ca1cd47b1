// P13: where a job's upload bytes go and what the upload costs, format 1 (hex `r` rows) beside format 2 (run-length `rl`
// rows, job.md): bytes per cell, the upload's time on the simulated wire at 115200 baud (windowed, 1 ms one way, virtual
// time) as a ratio to the line rate (P1's measure), and that time as a share of the whole job (upload + exposing).
import { DialectLink } from '../app/src/device/dialect-link';
import { uploadSize } from '../app/src/job/upload-time';
import { LINE_RATE_BPS } from '../app/src/job/link-rate';
import { headerOf } from '../app/src/planner/job-header';
import { planAnyJob } from '../app/src/planner/job-plan';
import { encodeJobRecords } from '../app/src/protocol/job-encode';
import type { JobFormat, PrintJob } from '../app/src/protocol/job-types';
import '../app/src/sim/wasm/node-firmware';
import { SimWire } from '../app/src/sim/wire';
import { BENCH_MACHINE } from './planner.bench';
import { boardMask, fillMask, photoMask, type Mask } from './masks';

async function settle(wire: SimWire, p: Promise<unknown>): Promise<void> {
  let done = false;
  p.then(() => (done = true), () => (done = true));
  while (!done) {
    wire.runUntil(() => done, 5);
    await new Promise((resolve) => setImmediate(resolve));
  }
  await p;
}

/** The job's text split by what its bytes carry: record heads (`r <row> <col> `), cells or run tokens, newlines, the rest. */
function textShares(job: PrintJob, format: JobFormat): { heads: number; cells: number; newlines: number; other: number } {
  const s = { heads: 0, cells: 0, newlines: 0, other: 0 };
  encodeJobRecords(job, (rec) => {
    s.newlines++;
    if (rec.startsWith('r ') || rec.startsWith('rl ')) {
      const head = rec.split(' ', 3).join(' ').length + 1;
      s.heads += head;
      s.cells += rec.length - head;
    } else s.other += rec.length;
  }, format);
  return s;
}

/** Uploads the job to the simulated printer (the firmware as WebAssembly) and starts it: the upload's time, printer seconds. */
async function uploadSeconds(job: PrintJob, format: JobFormat): Promise<{ seconds: number; bytes: number }> {
  const wire = new SimWire({}, { latencyUs: 1000 });
  const link = new DialectLink(wire.host, { ...wire.clientOptions, maxWindow: 8 });
  await settle(wire, link.open(() => {}, () => {}));
  await settle(wire, link.command('G28'));
  link.jobFormat = format;
  const t0 = wire.printer.clock.now;
  const b0 = wire.carried.toPrinter;
  let verifiedAt = 0;
  await settle(wire, link.startJob(job, (p) => {
    if (p.bytesVerified === p.bytesTotal && !verifiedAt) verifiedAt = wire.printer.clock.now;
  }));
  return { seconds: ((verifiedAt || wire.printer.clock.now) - t0) / 1e6, bytes: wire.carried.toPrinter - b0 };
}

function jobOf(mask: Mask): PrintJob {
  return {
    name: mask.name, grid: { cols: mask.cols, rows: mask.rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 10000, y: 10000 },
    dose: { map: mask.name === 'photo' ? 'linear' : 'threshold', level: 128, fullUs: 4000 }, leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'serpentine' }, gridData: mask.cells,
  };
}

export async function p13(): Promise<void> {
  console.log('\nP13 upload of a 30 x 30 mm job (600 x 600 cells at 50 µm), format 1 (r rows) against format 2 (rl rows)');
  console.log('  mask    format  text B   wire B   B/cell  heads/cells/newlines/framing (% of wire)   upload   of line rate  exposing   upload share   ratio to f1');
  for (const mask of [fillMask(600, 600), boardMask(600, 600, 9), photoMask(600, 600)]) {
    const job = jobOf(mask);
    const exposingS = planAnyJob({ header: headerOf(job), cells: job.gridData }, BENCH_MACHINE).plan.estimateUs / 1e6;
    let f1 = 0;
    for (const format of [1, 2] as const) {
      const size = uploadSize(job, format);
      const t = textShares(job, format);
      const up = await uploadSeconds(job, format);
      const framing = size.wireBytes - size.textBytes;
      const pct = (n: number) => ((100 * n) / size.wireBytes).toFixed(0).padStart(2);
      const share = up.seconds / (up.seconds + exposingS);
      if (format === 1) f1 = up.seconds;
      console.log(`  ${mask.name.padEnd(6)}  ${format}       ${String(size.textBytes).padStart(7)}  ${String(size.wireBytes).padStart(7)}  ${(size.wireBytes / size.cells).toFixed(3)}   ${pct(t.heads)}/${pct(t.cells)}/${pct(t.newlines)}/${pct(framing)}                      ${up.seconds.toFixed(1).padStart(6)} s  ${((100 * up.bytes) / (up.seconds * LINE_RATE_BPS)).toFixed(1).padStart(5)} %      ${exposingS.toFixed(0).padStart(6)} s  ${(100 * share).toFixed(1).padStart(5)} %        ${(up.seconds / f1).toFixed(3)}x`);
    }
  }
  console.log('  (wire B: records as numbered lines N<n> … *<xor>#<crc16>; upload: M28 to the last record verified, windowed, 1 ms one way; exposing: the planner\'s serpentine estimate)');
}
