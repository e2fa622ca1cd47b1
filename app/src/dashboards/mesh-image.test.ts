import { describe, expect, it } from 'vitest';
import { meshImage, zColour } from './mesh-image';

const mesh = { nx: 2, ny: 2, x0: 0, y0: 0, dx: 100_000, dy: 50_000, z: [[-40, 0], [0, 40]] };

describe('meshImage', () => {
  it('keeps the mesh aspect and puts the probed points on its corners', () => {
    const img = meshImage(mesh, 101);
    expect([img.width, img.height, img.spanUm]).toEqual([101, 51, 40]);
    expect(img.points).toEqual([{ x: 0, y: 0, zUm: -40 }, { x: 100, y: 0, zUm: 0 }, { x: 0, y: 50, zUm: 0 }, { x: 100, y: 50, zUm: 40 }]);
  });

  it('colours each pixel by the interpolated Z: full blue low, white level, full red high', () => {
    const img = meshImage(mesh, 101);
    const px = (x: number, y: number) => Array.from(img.rgba.slice((y * 101 + x) * 4, (y * 101 + x) * 4 + 3));
    expect(px(0, 0)).toEqual([33, 102, 172]);
    expect(px(100, 50)).toEqual([178, 24, 43]);
    expect(px(50, 25)).toEqual([255, 255, 255]); // the middle: (−40 + 0 + 0 + 40) / 4
    expect(zColour(20, 40)).toEqual([217, 140, 149]);
  });
});
