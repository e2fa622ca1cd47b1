// Web Worker host of the simulated printer: bytes in and out by postMessage, real time as its clock
// (times `speed`, which demos and tests may raise with ?simSpeed=N on the app's URL, and the simulated
// printer's panel changes live), and a reset of its Mega each time the app opens its link again
// (DTR): its memory goes, the printhead runs on.
// Its card, checkpoint, EEPROM and start count are kept in the browser (sim-storage.ts), so a reload
// finds the same machine: one that ran its job on while no page was there, then had its link opened.

import type { FromSimulator, Keeping, ToSimulator } from './sim-messages';
import { keepingNote, SimKeeper } from './sim-keeper';
import { SimPrinter } from './sim-printer';
import type { Kept } from './sim-snapshot';
import { claimStore, loadKept, writeKept } from './sim-storage';

const say = (m: FromSimulator) => postMessage(m);
let sending = '';
/** Bytes for the host, one message per task: at 200x a tick holds hundreds of reports, and the page handles each message in one go. */
function send(bytes: string): void {
  if (!bytes) return;
  if (!sending) queueMicrotask(() => {
    say({ type: 'rx', bytes: sending });
    sending = '';
  });
  sending += bytes;
}
let speed = 1;
let start = performance.now();
let printer: SimPrinter | null = null;
let keeper: SimKeeper | null = null;
const early: ToSimulator[] = []; // what the app sent while the store was being read

onmessage = (e: MessageEvent<ToSimulator>) => (printer ? obey(printer, e.data) : early.push(e.data));

function obey(p: SimPrinter, m: ToSimulator): void {
  if (m.type === 'tx') p.receive(m.bytes);
  else if (m.type === 'reset') p.resetMega(); // the link was opened again
  else if (m.type === 'speed') {
    speed = Math.max(1, Math.min(1000, m.speed));
    start = performance.now() - p.clock.now / 1000 / speed;
  } else if (m.type === 'faults') p.setFaults(m.faults);
  else if (m.type === 'unplug') p.unplug();
  else if (m.type === 'off') void (keeper?.switchOff() ?? Promise.resolve()).finally(() => close());
}

async function read(): Promise<{ kept: Kept; keeping: Keeping }> {
  if (!(await claimStore())) return { kept: { saved: null, running: null, note: null }, keeping: 'another tab' };
  try {
    return { kept: await loadKept(), keeping: 'kept' };
  } catch {
    return { kept: { saved: null, running: null, note: null }, keeping: 'unavailable' };
  }
}

async function boot(): Promise<void> {
  const { kept, keeping } = await read();
  const p = new SimPrinter(send, { saved: kept.saved });
  p.onDisconnect = () => say({ type: 'closed' });
  if (kept.running) {
    // The page that ran it went away mid-job; the printer ran on meanwhile, at the speed it had.
    p.runOn(kept.running.pos, (Date.now() - kept.running.atMs) * kept.running.speed);
    p.resetMega(); // and this page opens its link
  } else p.boot();
  printer = p;
  if (keeping === 'kept') {
    keeper = new SimKeeper(p, writeKept, () => speed, () => say({ type: 'kept', keeping: 'failed', note: keepingNote('failed', null), faults: p.faults }));
  }
  say({ type: 'kept', keeping, note: keepingNote(keeping, kept.note), faults: p.faults });
  start = performance.now() - p.clock.now / 1000 / speed;
  for (const m of early.splice(0)) obey(p, m);
  setInterval(() => {
    p.tick((performance.now() - start) * speed);
    void keeper?.keep();
  }, 20);
}

void boot();
