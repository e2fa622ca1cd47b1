// What the ESP's flash image has in place of sim-transport.ts (vite --mode esp): the app served by
// the printer's own hub talks to that printer, and the simulated one (16 KB gzipped) would take
// flash the job spool needs (protocol/esp.md). Choosing it says so instead of failing silently.

import type { Transport } from './transport';

export const SIMULATOR_BUILT_IN = false;

export class SimTransport implements Transport {
  readonly kind = 'sim' as const;

  async open(): Promise<void> {
    throw new Error('the app served by the printer has no simulated printer: open the app from npm start or a release build to try it');
  }

  async send(): Promise<void> {}

  async close(): Promise<void> {}
}

export function switchOffSimulatedPrinter(): void {}

export function tellSimulator(): void {}

export function setSimulatorSpeed(): void {}

export const loadSimulatorPanel = (): Promise<never> => Promise.reject(new Error('no simulated printer in the app served by the printer'));
