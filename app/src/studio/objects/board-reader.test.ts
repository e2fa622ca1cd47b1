// A board object read again as a project opens it (READERS' 'board'): its doses follow the object's choices.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { NEUTRAL_TONE } from '../image/adjust';
import { readArtwork } from './artwork';
import { newBoardFields } from './board-object';
import type { BoardObject } from './objects';

const DIR = join(import.meta.dirname, '../../../../e2e/fixtures/pcb');
const FILES = readdirSync(DIR).filter((f) => f.startsWith('demo-')).sort().map((name) => ({ name, text: readFileSync(join(DIR, name), 'utf8') }));

describe('a board in a project', () => {
  it('is read from its embedded files and exposes the layers the object chooses, at any size', async () => {
    const { boardSrc } = await import('../../pcb');
    const src = boardSrc(FILES);
    const kinds = ['copper-bottom', 'outline', 'copper-top', 'mask-top', 'drill'] as const;
    const o: BoardObject = {
      id: 1, kind: 'board', name: 'demo', src, x: 0, y: 0, w: 301, h: 201, halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE },
      ...newBoardFields(FILES.map((f, i) => ({ file: f.name, kind: kinds[i] }))),
    };
    const art = await readArtwork(o);
    expect(art.pixels).toEqual({ width: 30100, height: 20100 }); // the window in µm
    const top = art.doses(o, 301, 201);
    const at = (d: Uint8Array, x: number, y: number) => d[Math.floor((20.05 - y) / 0.1) * 301 + Math.floor((x + 0.05) / 0.1)];
    expect(at(top, 5.6, 5)).toBe(255); // the square pad's copper, exposed
    expect(at(top, 27, 2)).toBe(0);
    const none = art.doses({ ...o, layers: o.layers.map((l) => ({ ...l, expose: false })) }, 301, 201);
    expect(none.every((d) => d === 0)).toBe(true);
  });
});
