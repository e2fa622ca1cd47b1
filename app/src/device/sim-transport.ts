// Transport to the simulated printer running in a Web Worker. Like a real machine, it keeps running
// while no link is open, and opening the link restarts it, as opening a Mega's USB port does (DTR):
// what was in its memory is gone, and its SD card, with a running job's checkpoint, is kept. It is
// switched off when the app connects to a real printer.

import type { Transport } from './transport';

/** False in the ESP's flash image, which has sim-absent.ts in this module's place. */
export const SIMULATOR_BUILT_IN = true;

let machine: Worker | null = null;
let listener: ((bytes: string) => void) | null = null;

export class SimTransport implements Transport {
  readonly kind = 'sim' as const;

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
    const speed = Number(new URLSearchParams(location.search).get('simSpeed') ?? '1');
    if (speed > 1) machine.postMessage({ type: 'init', speed });
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
