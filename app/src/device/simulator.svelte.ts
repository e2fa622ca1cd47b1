// What the app knows of the simulated printer besides its bytes: whether the browser keeps it and what
// its store lost (the worker's words), its faults and its speed, for the page and the simulated printer's panel.

import type { Keeping } from '../sim/sim-messages';
import { NO_FAULTS, type SimFaults } from '../sim/sim-faults';

export const simulator = $state<{
  keeping: Keeping | null;
  note: string | null;
  faults: SimFaults;
  speed: number;
  panel: { frame: Uint8Array; rows: string[] } | null;
  printerUs: number | null;
}>({
  keeping: null,
  note: null,
  faults: { ...NO_FAULTS },
  speed: 1,
  /** The Mega's OLED, as its firmware last drew it (sim-messages.ts `panel`). */
  panel: null,
  /** The printer's own time since power-up (sim-messages.ts `clock`): behind the page's times the speed when it cannot keep up. */
  printerUs: null,
});
