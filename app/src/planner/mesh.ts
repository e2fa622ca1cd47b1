// Z offset from a probed mesh by bilinear interpolation (protocol/planner.md "Mesh interpolation").

export interface Mesh {
  nx: number;
  ny: number;
  x0: number;
  y0: number;
  dx: number;
  dy: number;
  /** z[j][i] in µm. */
  z: number[][];
}

/** round(n / d), half away from zero, exactly for |n| < 2^53, d > 0. */
function roundDivSigned(n: number, d: number): number {
  const a = Math.abs(n);
  let q = Math.floor(a / d);
  while (q * d > a) q--;
  while ((q + 1) * d <= a) q++;
  if (2 * (a - q * d) >= d) q++;
  return n < 0 && q !== 0 ? -q : q; // never -0
}

export function meshZ(m: Mesh, x: number, y: number): number {
  const cx = Math.min(Math.max(x, m.x0), m.x0 + (m.nx - 1) * m.dx);
  const cy = Math.min(Math.max(y, m.y0), m.y0 + (m.ny - 1) * m.dy);
  const i = Math.min(Math.floor((cx - m.x0) / m.dx), m.nx - 2);
  const j = Math.min(Math.floor((cy - m.y0) / m.dy), m.ny - 2);
  const u = cx - (m.x0 + i * m.dx);
  const w = cy - (m.y0 + j * m.dy);
  const n =
    m.z[j][i] * (m.dx - u) * (m.dy - w) + m.z[j][i + 1] * u * (m.dy - w) +
    m.z[j + 1][i] * (m.dx - u) * w + m.z[j + 1][i + 1] * u * w;
  return roundDivSigned(n, m.dx * m.dy);
}
