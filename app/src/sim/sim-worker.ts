// Web Worker host of the simulated printer (the firmware's C++ as WebAssembly, sim-printer.ts):
// bytes in and out by postMessage, real time as its clock (times `speed`, which demos and tests may
// raise with ?simSpeed=N on the app's URL, and the simulated printer's panel changes live), and a
// reset of its Mega each time the app opens its link again (DTR): its memory goes, the printhead
// runs on.
// Its card (with the job's checkpoint), EEPROM and start count are kept in the browser
// (sim-storage.ts), so a reload finds the same machine: one that ran its job on while no page was
// there, then had its link opened.

import type { FromSimulator, Keeping, ToSimulator } from './sim-messages';
import { keepingNote, SimKeeper } from './sim-keeper';
import { SimPrinter } from './sim-printer';
import type { Kept } from './sim-snapshot';
import { claimStore, loadKept, writeKept } from './sim-storage';
import { loadFirmwareModule } from './wasm/firmware-module';

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
const early: ToSimulator[] = []; // what the app sent while the module and the store were being read

onmessage = (e: MessageEvent<ToSimulator>) => (printer ? obey(printer, e.data) : early.push(e.data));

/**
 * The printer's time runs `speed` times the page's, but never more than this far ahead of what
 * the page last sent while its link is open: a page busy for a second at 40x would otherwise be a
 * host gone quiet for 40 s, and the Mega pauses a job whose hosts are silent for 30 s (mega.md §6).
 * The page's link speaks every 10 s of the printer's time (device/dialect-link.ts).
 */
const AHEAD_OF_HOST_US = 20_000_000;
let heardUs = 0;
let hostOpen = true; // the worker is made when the page opens its link

function obey(p: SimPrinter, m: ToSimulator): void {
  if (m.type === 'tx') {
    p.receive(m.bytes);
    heardUs = p.clock.now;
  } else if (m.type === 'reset') {
    p.resetMega(); // the link was opened again
    heardUs = p.clock.now;
    hostOpen = true;
  } else if (m.type === 'close') hostOpen = false; // the printer runs on at its own pace
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

let drawn = -1; // the OLED's draws the page has seen
let toldClockAt = -Infinity;
/** How often the page hears the printer's own time, ms of the page's. */
const CLOCK_EVERY_MS = 250;
/** The most of the machine's time one tick runs, in wall ms: a machine slower than asked falls behind rather than freeze its worker. */
const TICK_BUDGET_MS = 40;

async function boot(): Promise<void> {
  const [{ kept, keeping }] = await Promise.all([read(), loadFirmwareModule()]);
  const p = new SimPrinter(send, { saved: kept.saved });
  p.onDisconnect = () => say({ type: 'closed' });
  // The page that ran a job went away mid-job; the printer ran on meanwhile, at the speed it had.
  if (kept.running) p.runOn((Date.now() - kept.running.atMs) * kept.running.speed, kept.running.paced);
  p.resetMega(); // this page opens its link
  printer = p;
  if (keeping === 'kept') {
    keeper = new SimKeeper(p, writeKept, () => speed, () => say({ type: 'kept', keeping: 'failed', note: keepingNote('failed', null), faults: p.faults }));
  }
  say({ type: 'kept', keeping, note: keepingNote(keeping, kept.note), faults: p.faults });
  start = performance.now() - p.clock.now / 1000 / speed;
  for (const m of early.splice(0)) obey(p, m);
  setInterval(() => {
    const began = performance.now();
    let target = (began - start) * speed * 1000;
    if (hostOpen && !p.disconnected) target = Math.min(target, heardUs + AHEAD_OF_HOST_US);
    // In slices, so that a machine slower than its speed gives up the rest of the tick, and its
    // clock starts again from where it got: the page sees a slower printer, never a frozen one.
    while (p.clock.now < target && performance.now() - began < TICK_BUDGET_MS) p.advanceTo(Math.min(target, p.clock.now + 20_000 * speed));
    if (p.clock.now < target) start = performance.now() - p.clock.now / 1000 / speed;
    void keeper?.keep();
    if (performance.now() - toldClockAt >= CLOCK_EVERY_MS) {
      toldClockAt = performance.now();
      say({ type: 'clock', us: p.clock.now });
    }
    if (p.module.displayDraws !== drawn) {
      drawn = p.module.displayDraws;
      say({ type: 'panel', frame: p.module.displayFrame(), rows: p.module.display() });
    }
  }, 20);
}

void boot();
