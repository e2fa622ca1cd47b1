// Transport to the simulated printer running in a Web Worker. Like a real machine, it keeps running
// while no link is open, and opening the link restarts it, as opening a Mega's USB port does (DTR):
// what was in its memory is gone, and its SD card, with a running job's checkpoint, is kept. It is
// switched off when the app connects to a real printer.

import type { Transport } from './transport';

/** False in the ESP's flash image, which has sim-absent.ts in this module's place. */
export const SIMULATOR_BUILT_IN = true;

let machine: Worker | null = null;
let listener: ((bytes: string) => void) | null = null;

/** ?simSpeed=N runs the simulated printer N times real time (the worker's clock; at least 1). */
function simSpeed(): number {
  const n = Number(new URLSearchParams(location.search).get('simSpeed') ?? '1');
  return Number.isFinite(n) ? Math.max(1, Math.min(1000, n)) : 1;
}

export class SimTransport implements Transport {
  readonly kind = 'sim' as const;
  readonly timeScale = simSpeed();

  async open(onBytes: (bytes: string) => void): Promise<void> {
    listener = onBytes;
    if (machine) {
      machine.postMessage({ type: 'reset' });
      return;
    }
    machine = new Worker(new URL('../sim/sim-worker.ts', import.meta.url), { type: 'module' });
    machine.onmessage = (e: MessageEvent<{ type: 'rx'; bytes: string }>) => {
      if (e.data.type === 'rx') listener?.(e.data.bytes);
    };
    if (this.timeScale > 1) machine.postMessage({ type: 'init', speed: this.timeScale });
  }

  async send(bytes: string): Promise<void> {
    machine?.postMessage({ type: 'tx', bytes });
  }

  async close(): Promise<void> {
    listener = null;
  }
}

/** Connecting to a real printer switches the simulated one off: its card goes with it. */
export function switchOffSimulatedPrinter(): void {
  machine?.terminate();
  machine = null;
  listener = null;
}
