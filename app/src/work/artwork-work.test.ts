// A board's files read in the work worker, as an import or a project opened sends them: its rasters follow the object's choices.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { NEUTRAL_TONE } from '../studio/image/adjust';
import { newBoardFields } from '../studio/objects/board-object';
import type { BoardObject } from '../studio/objects/objects';
import { rasterInWorker, readBoard } from './artwork-work';
import type { Progress } from './work-types';

const DIR = join(import.meta.dirname, '../../../e2e/fixtures/pcb');
const FILES = readdirSync(DIR).filter((f) => f.startsWith('demo-')).sort().map((name) => ({ name, text: readFileSync(join(DIR, name), 'utf8') }));

describe('a board in a project', () => {
  it('is read from its embedded files and exposes the layers the object chooses, at any size', async () => {
    const stages: Progress[] = [];
    const read = readBoard({ files: FILES }, (p) => stages.push(p));
    const src = read.src;
    expect(read.kinds.map((k) => k.kind)).toEqual(['copper-bottom', 'outline', 'copper-top', 'mask-top', 'drill']);
    expect(stages.map((p) => p.stage)).toEqual(['reading the board']);
    const kinds = ['copper-bottom', 'outline', 'copper-top', 'mask-top', 'drill'] as const;
    const o: BoardObject = {
      id: 1, kind: 'board', name: 'demo', src, x: 0, y: 0, w: 300, h: 200, halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE },
      ...newBoardFields(FILES.map((f, i) => ({ file: f.name, kind: kinds[i] }))),
    };
    expect(read.pixels).toEqual({ width: 30000, height: 20000 }); // the window in µm: the outline's centre line
    expect(readBoard({ src }, () => stages.push({ stage: 'again' })).pixels).toEqual(read.pixels); // kept: not read again
    expect(stages).toHaveLength(1);
    const top = await rasterInWorker(o, 'negative', () => {});
    const at = (d: Uint8Array, x: number, y: number) => d[Math.floor((20 - y) / 0.1) * 300 + Math.floor(x / 0.1)];
    expect(at(top, 5.6, 5)).toBe(255); // the square pad's copper, exposed
    expect(at(top, 27, 2)).toBe(0);
    const none = await rasterInWorker({ ...o, layers: o.layers.map((l) => ({ ...l, expose: false })) }, 'negative', () => {});
    expect(none.every((d) => d === 0)).toBe(true);
    const positive = await rasterInWorker(o, 'positive', () => {});
    expect(at(positive, 5.6, 5)).toBe(0); // positive resist: the copper kept dark
    expect(at(positive, 27, 2)).toBe(255);
  });
});
