// The messages between the app and the simulated printer's worker (sim-worker.ts, device/sim-transport.ts).

import type { SimFaults } from './sim-faults';

export type ToSimulator =
  /** Bytes from the host. */
  | { type: 'tx'; bytes: string }
  /** The host opened the link again: the printer restarts, as a Mega does when its USB port opens. */
  | { type: 'reset' }
  /** The printer's speed, times real time (1-1000). */
  | { type: 'speed'; speed: number }
  | { type: 'faults'; faults: Partial<SimFaults> }
  /** The host closed its link (Disconnect): the printer runs on, nobody listening. */
  | { type: 'close' }
  /** The USB cable comes out: the printer runs on, the host's link is lost. */
  | { type: 'unplug' }
  /** Switched off (the app connects to a real printer): a job stops, and the worker ends. */
  | { type: 'off' };

/** Whether this printer is kept in the browser: 'another tab' keeps its own, 'unavailable' has no store. */
export type Keeping = 'kept' | 'another tab' | 'unavailable' | 'failed';

export type FromSimulator =
  /** Bytes to the host. */
  | { type: 'rx'; bytes: string }
  /** The link dropped (the cable came out). */
  | { type: 'closed' }
  /** How the printer is kept, and what the store's reading found wrong, if anything. */
  | { type: 'kept'; keeping: Keeping; note: string | null; faults: SimFaults }
  /** The Mega's OLED as its firmware last drew it: the SSD1306's 1024 bytes (8 pages × 128 columns). */
  | { type: 'panel'; frame: Uint8Array; rows: string[] }
  /** The printer's own time since it was powered up, µs (each quarter second of the page's). */
  | { type: 'clock'; us: number };
