// A board's raster drawn by the work worker (here its answers in the same thread): null until it is
// in, then the editor is told to redraw; a look known by everything but its place and its file.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it, vi } from 'vitest';
import { inThreadPort } from '../../work/in-thread.fixture';
import { WorkClient } from '../../work/work-client';
import { NEUTRAL_TONE } from '../image/adjust';
import { newBoardFields } from './board-object';
import type { BoardObject } from './objects';
import { lookKey, remoteArtwork } from './remote-artwork';
import type { BoardRead } from '../../work/work-types';

const DIR = join(import.meta.dirname, '../../../../e2e/fixtures/pcb');
const FILES = readdirSync(DIR).filter((f) => f.startsWith('demo-')).sort().map((name) => ({ name, text: readFileSync(join(DIR, name), 'utf8') }));

describe('artwork drawn off the page\'s thread', () => {
  it('is null until its raster is in, then redraws, and settles', async () => {
    const client = new WorkClient(inThreadPort);
    const read = await client.call<BoardRead>({ kind: 'read-board', files: FILES });
    const o: BoardObject = { id: 1, kind: 'board', name: 'demo', src: read.src, x: 0, y: 0, w: 301, h: 201, halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE }, ...newBoardFields(read.kinds) };
    const art = remoteArtwork(read.pixels, client);
    const redraw = vi.fn();
    art.whenDrawn!(redraw);
    expect(art.drawn!(o, 'negative')).toBeNull();
    await art.settle!(o, 'negative');
    expect(redraw).toHaveBeenCalledTimes(1);
    const raster = art.drawn!(o, 'negative')!;
    expect(raster).toHaveLength(301 * 201);
    expect(raster.some((d) => d === 255)).toBe(true);
    expect(art.drawn!({ ...o, x: 50, y: 9 }, 'negative')).toBe(raster); // moved: the same raster
    expect(art.drawn!(o, 'positive')).toBeNull(); // another look: drawn again
  });

  it('knows a look by everything but where it lies and its file', () => {
    const o = { id: 1, kind: 'image', name: 'p', src: 'data:a', x: 0, y: 0, w: 10, h: 5, halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE } } as const;
    expect(lookKey({ ...o, id: 2, x: 7, y: 3, src: 'data:b' }, 'negative')).toBe(lookKey(o, 'negative'));
    expect(lookKey({ ...o, threshold: 60 }, 'negative')).not.toBe(lookKey(o, 'negative'));
    expect(lookKey(o, 'positive')).not.toBe(lookKey(o, 'negative'));
  });
});
