// The mesh as a heatmap: every pixel the bilinear Z the Mega applies there (planner/mesh.ts), on a
// diverging scale (blue low, white level, red high), and where the probed points sit on it.

import { meshZ, type Mesh } from '../planner/mesh';

/** The colour of z on a scale of ±spanUm: blue below, white at 0, red above. */
export function zColour(zUm: number, spanUm: number): [number, number, number] {
  const t = Math.max(-1, Math.min(1, spanUm > 0 ? zUm / spanUm : 0));
  const fade = (c: number) => Math.round(255 - (255 - c) * Math.abs(t));
  return t < 0 ? [fade(33), fade(102), fade(172)] : [fade(178), fade(24), fade(43)];
}

export interface MeshImage {
  rgba: Uint8ClampedArray<ArrayBuffer>;
  width: number;
  height: number;
  spanUm: number;
  /** The probed points in image pixels, with their Z. */
  points: { x: number; y: number; zUm: number }[];
}

/** The area the points span, `width` pixels wide, keeping its aspect. */
export function meshImage(m: Mesh, width: number): MeshImage {
  const wUm = (m.nx - 1) * m.dx, hUm = (m.ny - 1) * m.dy;
  const height = Math.max(2, Math.round((width * hUm) / wUm));
  const spanUm = Math.max(1, ...m.z.flat().map(Math.abs));
  const rgba = new Uint8ClampedArray(width * height * 4);
  for (let py = 0; py < height; py++)
    for (let px = 0; px < width; px++) {
      const z = meshZ(m, m.x0 + Math.round((px / (width - 1)) * wUm), m.y0 + Math.round((py / (height - 1)) * hUm));
      const [r, g, b] = zColour(z, spanUm);
      const i = (py * width + px) * 4;
      rgba[i] = r, rgba[i + 1] = g, rgba[i + 2] = b, rgba[i + 3] = 255;
    }
  const points = m.z.flatMap((row, j) => row.map((zUm, i) => ({ x: (i / (m.nx - 1)) * (width - 1), y: (j / (m.ny - 1)) * (height - 1), zUm })));
  return { rgba, width, height, spanUm, points };
}
