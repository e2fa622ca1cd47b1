// The thermal chart's time axis: the printer's seconds as time before the newest sample, over a
// window that grows with the history (a minute at first, twenty at most), with ticks and words that
// say what they are from the first sample on.

import { HISTORY_S } from '../device/thermal-history';

/** Seconds before the newest sample (0 is now, -90 a minute and a half ago), for the time axis. */
export function secondsAgo(times: number[]): number[] {
  const newest = times.at(-1) ?? 0;
  return times.map((t) => t - newest);
}

/** The axis' windows, each with a tick step that gives it five or six whole ticks. */
const WINDOWS: readonly { spanS: number; stepS: number }[] = [
  { spanS: 60, stepS: 15 },
  { spanS: 120, stepS: 30 },
  { spanS: 300, stepS: 60 },
  { spanS: 600, stepS: 120 },
  { spanS: HISTORY_S, stepS: 300 },
];

export interface TimeAxis {
  /** The axis runs from -spanS to 0, seconds before now. */
  spanS: number;
  /** Where its ticks are, in seconds before now, oldest first; the last is 0. */
  ticks: number[];
}

/** The smallest window that holds `historyS` seconds of samples, and its ticks. */
export function timeAxis(historyS: number): TimeAxis {
  const w = WINDOWS.find((w) => historyS <= w.spanS) ?? WINDOWS[WINDOWS.length - 1];
  const ticks: number[] = [];
  for (let s = -w.spanS; s <= 0; s += w.stepS) ticks.push(s);
  return { spanS: w.spanS, ticks };
}

/** Seconds before now in words: "now", "-45 s", "-2 min", "-2 min 30 s". */
export function agoLabel(s: number): string {
  const whole = Math.round(s);
  if (whole === 0) return 'now';
  const min = Math.trunc(whole / 60), sec = Math.abs(whole % 60);
  if (!min) return `${whole} s`;
  return sec ? `${min} min ${sec} s` : `${min} min`;
}
