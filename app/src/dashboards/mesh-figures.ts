// The figures people judge a probed bed by: its range and spread, and the change since the mesh
// before. The mesh dashboard's alone, so they load with it.

import type { Mesh } from '../planner/mesh';

export interface MeshStats {
  minUm: number;
  maxUm: number;
  rangeUm: number;
  /** Standard deviation of the probed points, µm. */
  sdUm: number;
}

export function meshStats(m: Mesh): MeshStats {
  const all = m.z.flat();
  const mean = all.reduce((a, b) => a + b, 0) / all.length;
  const minUm = Math.min(...all), maxUm = Math.max(...all);
  return { minUm, maxUm, rangeUm: maxUm - minUm, sdUm: Math.sqrt(all.reduce((a, b) => a + (b - mean) ** 2, 0) / all.length) };
}

/** Point by point, `now − before`, when both meshes probe the same points; else null. */
export function meshDifference(now: Mesh, before: Mesh): Mesh | null {
  const same = now.nx === before.nx && now.ny === before.ny && now.x0 === before.x0 && now.y0 === before.y0 && now.dx === before.dx && now.dy === before.dy;
  return same ? { ...now, z: now.z.map((row, j) => row.map((v, i) => v - before.z[j][i])) } : null;
}

/**
 * Why the mesh cannot be compared with the previous one, in words, or null when it can: the
 * "compare" checkbox said nothing when it was closed (issue 29, item 14).
 */
export function compareWhy(now: Mesh | null, before: Mesh | null): string | null {
  if (!now) return 'no mesh yet: probe the bed, then probe it again to compare';
  if (!before) return 'one mesh so far: probe the bed again, and the change since this one is shown';
  if (now.nx !== before.nx || now.ny !== before.ny) return `the previous mesh has ${before.nx} × ${before.ny} points and this one ${now.nx} × ${now.ny}: probe with the same points to compare`;
  if (!meshDifference(now, before)) return 'the previous mesh probed other places on the bed (its margin or the bed changed): probe again to compare';
  return null;
}
