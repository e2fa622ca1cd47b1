// Paced jobs (protocol/mega.md "Pacing"): before each stop, and before each pass on the move, the
// Mega looks at its latest temperature reading and, when a sensor is near its soft limit, waits with
// the LEDs off until the head has cooled. The rule and its constants, shared by the simulated Mega and the dry run's forecast; the
// firmware has the same numbers (firmware/mega/src/job_runner.h).

/** The Mega reads the printhead's temperatures this often (T), µs. */
export const READING_PERIOD_US = 500_000;
/** A paced job waits before a stop or a pass when a sensor reads this close to its soft limit, 0.1 °C. */
export const PACE_AT_DECIC = 20;
/** …and goes on once every sensor reads at least this far below it, 0.1 °C. */
export const PACE_UNTIL_DECIC = 30;

/**
 * Whether a paced job waits now. `readingDeciC` is the latest reading, `limitDeciC` the soft limits;
 * `cooling` says whether it is already waiting (the hysteresis between the two lines).
 */
export function paceWaits(readingDeciC: readonly number[], limitDeciC: readonly number[], cooling: boolean): boolean {
  const margin = cooling ? PACE_UNTIL_DECIC : PACE_AT_DECIC;
  return readingDeciC.some((t, i) => (cooling ? t > limitDeciC[i] - margin : t >= limitDeciC[i] - margin));
}

/** The sensor at or over its soft limit in a reading, or -1: an unpaced job pauses there. */
export function overSoftLimit(readingDeciC: readonly number[], limitDeciC: readonly number[]): number {
  return readingDeciC.findIndex((t, i) => t >= limitDeciC[i]);
}
