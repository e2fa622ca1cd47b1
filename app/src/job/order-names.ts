// The Order list's words for each strategy, shared by the job panel and the preview.

import type { StrategyName } from '../protocol/job-types';

export const ORDER_NAMES: Record<StrategyName, string> = {
  scan: 'Scan (on the move)',
  mixed: 'Mixed (each pass on the move or by stops)',
  serpentine: 'Serpentine',
  raster: 'Raster',
  shortest: 'Shortest travel',
  random: 'Random (spreads the heat)',
};

/** The list's order, the automatic choice first. */
export const ORDER_LIST: StrategyName[] = ['scan', 'mixed', 'serpentine', 'raster', 'shortest', 'random'];

/** An estimate as the list shows it beside an order: "53 min", "1 h 05 min", "40 s". */
export function estimateWords(us: number | undefined): string {
  if (us === undefined || !Number.isFinite(us)) return '';
  const s = Math.round(us / 1e6);
  if (s < 60) return `${s} s`;
  const m = Math.round(s / 60);
  return m < 60 ? `${m} min` : `${Math.floor(m / 60)} h ${String(m % 60).padStart(2, '0')} min`;
}
