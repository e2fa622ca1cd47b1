// The times a job is told in while it runs and when it ends: a paced job's (mega.md "Pacing") are its
// paced forecast's, as the question promised, not the Mega's, whose `remaining` does not foresee waits.

/** The estimates the user was shown for the job started here, µs; `pacedUs` null when none was offered. */
export interface JobEstimate {
  estimateUs: number;
  pacedUs: number | null;
}

/** The estimate the job is held to: its paced time when it runs paced and one was forecast. */
export function estimateUsFor(e: JobEstimate | null, paced: boolean): number | null {
  if (!e) return null;
  return paced && e.pacedUs !== null ? e.pacedUs : e.estimateUs;
}

/**
 * Seconds left. The Mega's `remaining` counts the stops' own time; paced, the forecast's waits are
 * spread over the job as its stops are, so what is left grows by the paced forecast's share.
 */
export function leftS(remainingS: number, e: JobEstimate | null, paced: boolean): number {
  if (!paced || !e || e.pacedUs === null || e.estimateUs <= 0) return remainingS;
  return Math.round((remainingS * e.pacedUs) / e.estimateUs);
}

/** "1 h 32 min", "4 min 5 s", "12 s". */
export function duration(s: number): string {
  if (s >= 3600) {
    const m = Math.round((s % 3600) / 60);
    return m === 60 ? `${Math.floor(s / 3600) + 1} h 0 min` : `${Math.floor(s / 3600)} h ${m} min`;
  }
  return s >= 60 ? `${Math.floor(s / 60)} min ${s % 60} s` : `${s} s`;
}
