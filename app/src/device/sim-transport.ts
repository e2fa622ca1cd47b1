// Transport to the simulated printer running in a Web Worker.

import type { Transport } from './transport';

export class SimTransport implements Transport {
  readonly kind = 'sim' as const;
  #worker: Worker | null = null;

  async open(onBytes: (bytes: string) => void): Promise<void> {
    this.#worker = new Worker(new URL('../sim/sim-worker.ts', import.meta.url), { type: 'module' });
    this.#worker.onmessage = (e: MessageEvent<{ type: 'rx'; bytes: string }>) => {
      if (e.data.type === 'rx') onBytes(e.data.bytes);
    };
    const speed = Number(new URLSearchParams(location.search).get('simSpeed') ?? '1');
    if (speed > 1) this.#worker.postMessage({ type: 'init', speed });
  }

  async send(bytes: string): Promise<void> {
    this.#worker?.postMessage({ type: 'tx', bytes });
  }

  async close(): Promise<void> {
    this.#worker?.terminate();
    this.#worker = null;
  }
}
