// The thermal chart's time axis: the printer's seconds as minutes before the newest sample.

/** Seconds to minutes before the newest sample (0 is now, -5 five minutes ago), for the time axis. */
export function minutesAgo(times: number[]): number[] {
  const newest = times.at(-1) ?? 0;
  return times.map((t) => (t - newest) / 60);
}

/** The time axis' words: "now", "-2 min", "-30 s" under a minute. */
export function agoLabel(min: number): string {
  if (Math.abs(min) < 1e-9) return 'now';
  if (Math.abs(min) < 1) return `${Math.round(min * 60)} s`;
  return `${Number(min.toFixed(1))} min`;
}
