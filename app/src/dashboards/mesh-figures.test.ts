import { describe, expect, it } from 'vitest';
import { parseMesh } from '../device/mesh-report';
import { compareWhy, meshDifference, meshStats } from './mesh-figures';

const lines = [
  'MESH:grid 3 2 x0=10.000 y0=10.000 dx=90.000 dy=180.000',
  'MESH:row 0 0.010 -0.020 0.000',
  'MESH:row 1 0.050 0.030 -0.010',
];

describe('meshStats and meshDifference', () => {
  it('gives the range and the spread of the probed points', () => {
    const s = meshStats(parseMesh(lines)!);
    expect([s.minUm, s.maxUm, s.rangeUm]).toEqual([-20, 50, 70]);
    expect(s.sdUm).toBeCloseTo(Math.sqrt(3400 / 6), 6); // mean 10 µm
  });

  it('compares two meshes of the same points, and no others', () => {
    const a = parseMesh(lines)!;
    const b = { ...a, z: a.z.map((r) => r.map((v) => v + 5)) };
    expect(meshDifference(b, a)!.z).toEqual([[5, 5, 5], [5, 5, 5]]);
    expect(meshDifference({ ...b, nx: 2, z: b.z.map((r) => r.slice(0, 2)) }, a)).toBeNull();
  });
});

describe('comparing with the previous mesh (issue 29, item 14)', () => {
  const mesh = parseMesh(lines)!;
  it('says why it cannot, in words, and nothing when it can', () => {
    expect(compareWhy(null, null)).toMatch(/^no mesh yet: probe the bed/);
    expect(compareWhy(mesh, null)).toMatch(/^one mesh so far: probe the bed again/);
    const finer = { ...mesh, nx: 4, z: mesh.z.map((r) => [...r, 0]) };
    expect(compareWhy(finer, mesh)).toBe('the previous mesh has 3 × 2 points and this one 4 × 2: probe with the same points to compare');
    expect(compareWhy({ ...mesh, x0: 20_000 }, mesh)).toMatch(/probed other places on the bed/);
    expect(compareWhy({ ...mesh, z: mesh.z.map((r) => r.map((v) => v + 5)) }, mesh)).toBeNull();
  });
});
