// The probed mesh from its `MESH:` report lines (protocol/mega.md §4). The figures people judge a bed
// by are the mesh dashboard's (dashboards/mesh-figures.ts).

import type { Mesh } from '../planner/mesh';

const um = (mm: string) => Math.round(Number(mm) * 1000);

/** `MESH:grid nx ny x0= y0= dx= dy=` then `MESH:row j z…` in mm; null while incomplete or unreadable. */
export function parseMesh(lines: string[]): Mesh | null {
  const g = /^MESH:grid (\d+) (\d+) x0=(-?[\d.]+) y0=(-?[\d.]+) dx=([\d.]+) dy=([\d.]+)$/.exec(lines[0] ?? '');
  if (!g) return null;
  const [nx, ny] = [Number(g[1]), Number(g[2])];
  const z: number[][] = [];
  for (const line of lines.slice(1)) {
    const m = /^MESH:row (\d+) (.+)$/.exec(line);
    if (!m) continue;
    const row = m[2].trim().split(/\s+/).map(um);
    if (row.length !== nx || row.some((v) => !Number.isFinite(v))) return null;
    z[Number(m[1])] = row;
  }
  if (nx < 2 || ny < 2 || z.length !== ny || z.some((r) => !r)) return null;
  return { nx, ny, x0: um(g[3]), y0: um(g[4]), dx: um(g[5]), dy: um(g[6]), z };
}
