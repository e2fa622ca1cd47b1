import { describe, expect, it } from 'vitest';
import { NEUTRAL_TONE } from '../image/adjust';
import { cutsOf, cutWords, isOffBed, overhang } from './clipping';
import type { FrameObject, ImageObject, StudioObject } from './objects';

const PITCH = { x: 50, y: 50 };
const picture = (over: Partial<ImageObject> = {}): ImageObject => ({
  kind: 'image', id: 1, x: 0, y: 0, w: 10, h: 4, name: 'board.png', src: 'data:p', halftone: 'threshold', threshold: 50, tone: { ...NEUTRAL_TONE }, ...over,
});
/** Every cell exposed. */
const solid = (o: StudioObject) => new Uint8Array(o.w * o.h).fill(255);

describe('objects cut by the bed\'s edge', () => {
  it('measures how far a box lies past each edge', () => {
    expect(overhang({ x: -3, y: 2, w: 10, h: 10 }, 20, 10)).toEqual({ left: 3, right: 0, top: 0, bottom: 2 });
    expect(isOffBed({ x: 0, y: 0, w: 20, h: 10 }, 20, 10)).toBe(false);
    expect(isOffBed({ x: 11, y: 0, w: 10, h: 10 }, 20, 10)).toBe(true);
  });

  it('says which objects lose exposed cells, by how much', () => {
    const cuts = cutsOf([picture({ x: 15 }), picture({ id: 2, x: 0, y: 0 })], solid, 20, 10, PITCH);
    expect(cuts).toEqual([{ id: 1, name: 'picture board.png', overhangMm: { left: 0, right: 0.25, top: 0, bottom: 0 }, lost: 20, lit: 40 }]);
    expect(cutWords(cuts[0])).toBe('picture board.png: 0.25 mm past the right edge; 50 % of its exposed cells are off the bed');
  });

  it('does not count a margin that exposes nothing, nor a guide frame', () => {
    // Only the left half of the picture is exposed; its right half hangs off the bed.
    const leftHalf = (o: StudioObject) => new Uint8Array(o.w * o.h).map((_, i) => (i % o.w < 5 ? 255 : 0));
    expect(cutsOf([picture({ x: 15 })], leftHalf, 20, 10, PITCH)).toEqual([]);
    const guide: FrameObject = { kind: 'frame', id: 3, x: -5, y: -5, w: 40, h: 40, line: 0, dose: 255 };
    expect(cutsOf([guide], solid, 20, 10, PITCH)).toEqual([]);
  });

  it('counts the whole box of an object whose raster is not ready yet', () => {
    expect(cutsOf([picture({ x: -5 })], () => null, 20, 10, PITCH)[0]).toMatchObject({ lost: 20, lit: 40 });
  });
});
