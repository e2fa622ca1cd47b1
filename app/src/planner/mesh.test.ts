import { expect, it } from 'vitest';
import { cases, loadVectors, vectorCounter } from '../protocol/vectors.fixture';
import { meshZ } from './mesh';

const v = loadVectors('mesh.json');
const count = vectorCounter('mesh.json');

it.each(cases(v.cases, 'name'))('mesh %s interpolates bilinearly and clamps', (_n, c) => {
  for (const [x, y, z] of c.points) {
    expect(meshZ(c.mesh, x, y), `${c.name} at ${x},${y}`).toBe(z);
    count();
  }
});
