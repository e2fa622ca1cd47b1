import { describe, expect, it } from 'vitest';
import { parseMesh } from './mesh-report';

const lines = [
  'MESH:grid 3 2 x0=10.000 y0=10.000 dx=90.000 dy=180.000',
  'MESH:row 0 0.010 -0.020 0.000',
  'MESH:row 1 0.050 0.030 -0.010',
];

describe('parseMesh', () => {
  it('reads the grid and its rows in µm', () => {
    expect(parseMesh(lines)).toEqual({ nx: 3, ny: 2, x0: 10_000, y0: 10_000, dx: 90_000, dy: 180_000, z: [[10, -20, 0], [50, 30, -10]] });
  });

  it('is null until every row is in, or for a row of the wrong length', () => {
    expect(parseMesh(lines.slice(0, 2))).toBeNull();
    expect(parseMesh([lines[0], 'MESH:row 0 0.010 -0.020', lines[2]])).toBeNull();
    expect(parseMesh([])).toBeNull();
  });
});
