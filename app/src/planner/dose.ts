// Cell value to exposure time per LED (protocol/planner.md "Durations"), in exact integer arithmetic:
// the dose units' rounding, and the spec's durations the tests and the bench hold the planner's plans to.

import type { JobHeader } from '../protocol/job-types';

/** round(n / d) half up for integers 0 <= n, 0 < d, with n < 2^53. */
export function roundDiv(n: number, d: number): number {
  let q = Math.floor(n / d);
  while (q * d > n) q--;
  while ((q + 1) * d <= n) q++;
  return 2 * (n - q * d) >= d ? q + 1 : q;
}

export function fullUs(h: JobHeader, led: number): number {
  if (h.fullUs !== undefined) return h.fullUs;
  return roundDiv(h.targetUJcm2! * 1_000_000, h.irradianceUWcm2![led]);
}

/** durations[led][value] in µs for values 0-255. */
export function durationTables(h: JobHeader): Uint32Array[] {
  return [0, 1, 2, 3].map((led) => {
    const scale = fullUs(h, led) * h.gainPermille[led];
    const table = new Uint32Array(256);
    for (let v = 1; v < 256; v++) {
      const m = h.map === 'linear' ? v : v >= h.level ? 255 : 0;
      table[v] = roundDiv(scale * m, 255000);
    }
    return table;
  });
}
