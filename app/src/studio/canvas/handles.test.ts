import { describe, expect, it } from 'vitest';
import { FRAME_PX, HANDLE_PX, handleAt, handleCentres, selectionFrame } from './handles';

/** The squares the handles cover, on the screen. */
const squares = (v: { scale: number; x: number; y: number }, r: { x: number; y: number; w: number; h: number }) =>
  handleCentres(v, r).map((h) => ({ x0: h.x - HANDLE_PX / 2, y0: h.y - HANDLE_PX / 2, x1: h.x + HANDLE_PX / 2, y1: h.y + HANDLE_PX / 2 }));

describe('the selection\'s handles', () => {
  // Issue 29, item 14: 5 mm text placed at the overview's zoom is 12 px high, and the handles covered its ends.
  it('sit outside a box small on the screen, covering none of it', () => {
    const overview = { scale: 0.12, x: 0, y: 0 };
    const text = { x: 1000, y: 1000, w: 240, h: 100 }; // 29 × 12 px
    for (const s of squares(overview, text)) {
      const [bx0, by0, bx1, by1] = [text.x * 0.12, text.y * 0.12, (text.x + text.w) * 0.12, (text.y + text.h) * 0.12];
      expect(s.x1 <= bx0 || s.x0 >= bx1 || s.y1 <= by0 || s.y0 >= by1).toBe(true);
    }
  });

  it('sit on the corners of a box large on the screen', () => {
    const v = { scale: 2, x: 0, y: 0 };
    expect(handleCentres(v, { x: 10, y: 10, w: 100, h: 50 })).toEqual([
      { corner: 'nw', x: 20, y: 20 },
      { corner: 'ne', x: 220, y: 20 },
      { corner: 'sw', x: 20, y: 120 },
      { corner: 'se', x: 220, y: 120 },
    ]);
  });

  it('are taken where they are drawn, and at the corner itself', () => {
    const overview = { scale: 0.12, x: 0, y: 0 };
    const text = { x: 1000, y: 1000, w: 240, h: 100 };
    for (const h of handleCentres(overview, text)) expect(handleAt(overview, text, h.x, h.y)).toBe(h.corner);
    expect(handleAt(overview, text, 120, 120)).toBe('nw');
    expect(handleAt(overview, text, 134, 126)).toBeNull(); // the middle of the text is the text's
  });
});

describe('the selection frame', () => {
  // Issue 41 item 6: new text at the overview's zoom was half hidden by a frame drawn on its edge.
  it('runs outside the box, its whole line off the object', () => {
    const overview = { scale: 0.12, x: 7, y: 3 };
    const text = { x: 1000, y: 1000, w: 240, h: 100 };
    const f = selectionFrame(overview, text);
    const box = { x0: (1000 - 7) * 0.12, y0: (1000 - 3) * 0.12, x1: (1240 - 7) * 0.12, y1: (1100 - 3) * 0.12 }; // 28.8 × 12 px
    // A line of FRAME_PX drawn on f's edges covers f ± FRAME_PX / 2: it ends before the box begins.
    expect(f.x + FRAME_PX / 2).toBeLessThanOrEqual(box.x0);
    expect(f.y + FRAME_PX / 2).toBeLessThanOrEqual(box.y0);
    expect(f.x + f.w - FRAME_PX / 2).toBeGreaterThanOrEqual(box.x1);
    expect(f.y + f.h - FRAME_PX / 2).toBeGreaterThanOrEqual(box.y1);
  });
});
