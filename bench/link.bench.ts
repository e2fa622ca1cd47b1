// P1: upload wire utilisation at 115200 baud, windowed sender against one line per ok, over the simulated wire
// (baud rate and one-way latency modelled, virtual time, so the figures do not depend on this machine's load).
import { DialectLink } from '../app/src/device/dialect-link';
import type { PrintJob } from '../app/src/protocol/job-types';
import '../app/src/sim/wasm/node-firmware';
import { SimWire } from '../app/src/sim/wire';
import { boardMask } from './masks';

const BAUD = 115200;

async function settle(wire: SimWire, p: Promise<unknown>): Promise<void> {
  let done = false;
  p.then(() => (done = true), () => (done = true));
  while (!done) {
    wire.runUntil(() => done, 5);
    await new Promise((resolve) => setImmediate(resolve)); // what the bytes settled runs, timers and all
  }
  await p;
}

/** Wire bytes per second of the upload, as a share of what 115200 baud can carry. */
async function utilisation(window: number, latencyUs: number, job: PrintJob): Promise<{ share: number; seconds: number; bytes: number }> {
  const wire = new SimWire({}, { latencyUs });
  const link = new DialectLink(wire.host, { ...wire.clientOptions, maxWindow: window });
  await settle(wire, link.open(() => {}, () => {}));
  await settle(wire, link.command('G28'));
  link.jobFormat = 1; // hex rows, as P1 has always measured them: P13 sets format 2 beside it
  const t0 = wire.printer.clock.now;
  const b0 = wire.carried.toPrinter;
  let uploaded = 0;
  await settle(wire, link.startJob(job, (p) => (uploaded = p.bytesVerified)));
  const seconds = (wire.printer.clock.now - t0) / 1e6;
  const bytes = wire.carried.toPrinter - b0;
  void uploaded;
  return { share: bytes / (seconds * (BAUD / 10)), seconds, bytes };
}

export async function p1(): Promise<void> {
  const mask = boardMask(400, 200, 9);
  const job: PrintJob = {
    name: 'p1', grid: { cols: mask.cols, rows: mask.rows }, pitchUm: { x: 50, y: 50 }, originUm: { x: 10000, y: 10000 },
    dose: { map: 'threshold', level: 128, fullUs: 2000 }, leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'serpentine' }, gridData: mask.cells,
  };
  console.log('\nP1 upload wire utilisation at 115200 baud (goal: windowed >= 90 % of the line rate)');
  console.log("  one-way latency   windowed (USB's 3 lines)  window 1 (one line per ok)   ratio");
  for (const latencyUs of [1000, 4000, 16000]) {
    const w = await utilisation(8, latencyUs, job);
    const one = await utilisation(1, latencyUs, job);
    console.log(`  ${String(latencyUs / 1000).padStart(5)} ms         ${(w.share * 100).toFixed(1).padStart(5)} % (${w.seconds.toFixed(1)} s)        ${(one.share * 100).toFixed(1).padStart(5)} % (${one.seconds.toFixed(1)} s)           ${(w.share / one.share).toFixed(2)}x`);
  }
  const esp = await utilisation(2, 1000, job);
  console.log(`  the ESP's port, 2 lines (mega.md §3) at 1 ms one way: ${(esp.share * 100).toFixed(1)} % (${esp.seconds.toFixed(1)} s)`);
  console.log(`  (${Math.round(job.gridData.length * job.grid.cols)} cells; the wire bytes include line numbers and checks)`);
}
