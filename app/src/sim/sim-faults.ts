// The faults the simulated printer models, as one value that can change while it runs: the simulated
// printer's panel sets them (issue 17, item 11), tests set them at construction.

import type { LinkFaults } from './link-faults';

export interface SimFaults {
  /** Chance per byte on the link, in %, that one bit flips (both directions). */
  corruptPercent: number;
  /** Chance per byte on the link, in %, that it is lost (both directions). */
  dropPercent: number;
  /** Every `stallEveryMs` the printer stops reading for `stallMs`; 0 for no stalls. */
  stallEveryMs: number;
  stallMs: number;
  /** °C per second each LED's sensor warms with no LED lit: the printhead overheats (0 for none). */
  overheatCPerS: number;
  /** The probe goes into alarm on its next deploy. */
  probeAlarm: boolean;
  /** No printhead answers. */
  missingNano: boolean;
}

export const NO_FAULTS: SimFaults = {
  corruptPercent: 0,
  dropPercent: 0,
  stallEveryMs: 0,
  stallMs: 0,
  overheatCPerS: 0,
  probeAlarm: false,
  missingNano: false,
};

/** The link's share of the faults, over what the link had (its seed, a disconnect to come). */
export function withLinkFaults(link: LinkFaults, f: SimFaults): LinkFaults {
  return { ...link, corruptPercent: f.corruptPercent, dropPercent: f.dropPercent, stallEveryMs: f.stallEveryMs, stallMs: f.stallMs };
}

/** Each field held to what the model takes: percentages 0-100, times and heating not negative. */
export function saneFaults(f: Partial<SimFaults>): SimFaults {
  const n = (v: unknown, max: number) => (typeof v === 'number' && Number.isFinite(v) ? Math.min(max, Math.max(0, v)) : 0);
  return {
    corruptPercent: n(f.corruptPercent, 100),
    dropPercent: n(f.dropPercent, 100),
    stallEveryMs: n(f.stallEveryMs, 3_600_000),
    stallMs: n(f.stallMs, 3_600_000),
    overheatCPerS: n(f.overheatCPerS, 1000),
    probeAlarm: f.probeAlarm === true,
    missingNano: f.missingNano === true,
  };
}
