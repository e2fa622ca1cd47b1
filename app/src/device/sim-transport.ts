// Transport to the simulated printer running in a Web Worker. Like a real machine, it keeps running
// while no link is open, and opening the link restarts it, as opening a Mega's USB port does (DTR):
// what was in its memory is gone, and its SD card, with a running job's checkpoint, is kept. The
// browser keeps the card, the checkpoint and the EEPROM, so a reload is a reconnect (sim-worker.ts).
// It is switched off when the app connects to a real printer.

import type { FromSimulator, ToSimulator } from '../sim/sim-messages';
import { simulator } from './simulator.svelte';
import type { Transport } from './transport';

/** False in the ESP's flash image, which has sim-absent.ts in this module's place. */
export const SIMULATOR_BUILT_IN = true;

let machine: Worker | null = null;
let listener: ((bytes: string) => void) | null = null;
let onLost: ((error?: Error) => void) | null = null;
let rescaled: (() => void) | null = null;

/** ?simSpeed=N runs the simulated printer N times real time (the worker's clock; at least 1). */
function simSpeed(): number {
  const n = Number(new URLSearchParams(location.search).get('simSpeed') ?? '1');
  return Number.isFinite(n) ? Math.max(1, Math.min(1000, n)) : 1;
}

function hear(m: FromSimulator): void {
  if (m.type === 'rx') listener?.(m.bytes);
  else if (m.type === 'closed') {
    const lost = onLost;
    listener = onLost = null;
    lost?.(new Error("the simulated printer's USB cable was pulled"));
  } else if (m.type === 'panel') simulator.panel = { frame: m.frame, rows: m.rows };
  else if (m.type === 'clock') simulator.printerUs = m.us;
  else Object.assign(simulator, { keeping: m.keeping, note: m.note, faults: m.faults });
}

export class SimTransport implements Transport {
  readonly kind = 'sim' as const;
  constructor() {
    simulator.speed = simSpeed();
  }
  /** The speed the worker runs at now: the URL's at first, then the panel's (setSimulatorSpeed). */
  get timeScale(): number {
    return simulator.speed;
  }
  set onRescaled(fn: (() => void) | null) {
    rescaled = fn;
  }

  async open(onBytes: (bytes: string) => void, onClosed: (error?: Error) => void): Promise<void> {
    listener = onBytes;
    onLost = onClosed;
    if (machine) {
      machine.postMessage({ type: 'reset' } satisfies ToSimulator);
      return;
    }
    machine = new Worker(new URL('../sim/sim-worker.ts', import.meta.url), { type: 'module' });
    machine.onmessage = (e: MessageEvent<FromSimulator>) => hear(e.data);
    if (this.timeScale > 1) tellSimulator({ type: 'speed', speed: this.timeScale });
  }

  async send(bytes: string): Promise<void> {
    tellSimulator({ type: 'tx', bytes });
  }

  async close(): Promise<void> {
    listener = onLost = rescaled = null;
    tellSimulator({ type: 'close' });
  }
}

/**
 * The simulated printer's speed, changed live (its panel): the worker's clock, and the link's
 * heartbeat with it. A heartbeat left at the old speed's period let the worker, which never runs
 * more than 20 s of its time past the page's last line, stall for most of each period at a faster
 * speed (the thermal chart's samples came in bursts, and its window ran ahead of the printer).
 */
export function setSimulatorSpeed(speed: number): void {
  simulator.speed = speed;
  tellSimulator({ type: 'speed', speed });
  rescaled?.();
}

/** A message to the running simulated printer (its panel: speed, faults, the cable). */
export function tellSimulator(m: ToSimulator): void {
  machine?.postMessage(m);
}

/** The simulated printer's panel, loaded when its tab is first opened (never in the ESP's image). */
export const loadSimulatorPanel = () => import('../dashboards/SimulatorPanel.svelte');

/** Connecting to a real printer switches the simulated one off: a job stops; the browser keeps its card. */
export function switchOffSimulatedPrinter(): void {
  machine?.postMessage({ type: 'off' } satisfies ToSimulator); // it writes that, then ends
  machine = null;
  listener = onLost = rescaled = null;
  simulator.keeping = simulator.note = null;
}
