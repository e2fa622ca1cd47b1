// How a scan job (exposure on the move), or a mixed one, is described wherever it is shown: the dry run, the preview.

import { mixedPassCount, type MixedPlan } from '../planner/plan';

export function scanWords(passes: number, speedUmS: number, windowUs: number): string {
  const mmS = speedUmS / 1000;
  return `${passes} pass${passes === 1 ? '' : 'es'} at ${mmS.toFixed(mmS < 10 ? 2 : 1)} mm/s, a ${(windowUs / 1000).toFixed(2)} ms window per cell`;
}

/** A mixed job's passes: how many run on the move, how many stop by stop (a band of stops counts its passes). */
export function mixedWords(mixed: Pick<MixedPlan, 'passes'>): string {
  const scans = mixed.passes.filter((p) => p.scan).length, all = mixedPassCount(mixed);
  return `${all} passes, ${scans} on the move and ${all - scans} stop by stop`;
}
