// The delivered-dose map's colours, one a cell state (dose-map.ts CellDose), told apart by people
// who do not see red and green apart (Okabe and Ito's palette), and the map binned for its canvas.

import { pixelWord } from '../preview/preview-colours';
import { CellDose, type DeliveredMap } from './dose-map';

export const DOSE_COLOURS: Record<number, string> = {
  [CellDose.None]: '#ffffff',
  [CellDose.Within]: '#009e73',
  [CellDose.Off]: '#e69f00',
  [CellDose.Dark]: '#1d2330',
  [CellDose.Waiting]: '#c9cdd6',
};
/** The mark on a cell lit twice. */
export const TWICE_COLOUR = '#cc79a7';

const hex = (h: string) => pixelWord([1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16)));
const WORDS = [CellDose.None, CellDose.Within, CellDose.Off, CellDose.Dark, CellDose.Waiting].map((s) => hex(DOSE_COLOURS[s]));
const TWICE_WORD = hex(TWICE_COLOUR);
/** Which state a bin of several cells shows: the one that most needs a look. */
const RANK = [0, 1, 3, 4, 2]; // None, Within, Off, Dark, Waiting → rank

/**
 * The map as pixels, `zoom` a cell (or a bin of `scale` × `scale` cells a pixel, for a grid over
 * `maxSide`): each in its state's colour, a cell lit twice with a mark in its middle (a bin: all of it).
 */
export function doseImage(m: DeliveredMap, maxSide: number): { width: number; height: number; zoom: number; pixels: Uint32Array<ArrayBuffer> } {
  const scale = Math.max(1, Math.ceil(Math.max(m.cols, m.rows) / maxSide));
  const bw = Math.ceil(m.cols / scale), bh = Math.ceil(m.rows / scale);
  const zoom = scale > 1 ? 1 : Math.max(1, Math.min(24, Math.floor(maxSide / Math.max(bw, bh))));
  const state = new Uint8Array(bw * bh), twice = new Uint8Array(bw * bh);
  for (let y = 0; y < m.rows; y++)
    for (let x = 0; x < m.cols; x++) {
      const c = y * m.cols + x, b = Math.floor(y / scale) * bw + Math.floor(x / scale);
      if (RANK[m.state[c]] > RANK[state[b]]) state[b] = m.state[c];
      twice[b] |= m.twice[c];
    }
  const width = bw * zoom, height = bh * zoom;
  const pixels = new Uint32Array(width * height);
  // The mark: the middle half of a cell, when a cell has room for one around it.
  const lo = Math.floor(zoom / 4), hi = zoom - lo;
  for (let by = 0; by < bh; by++)
    for (let bx = 0; bx < bw; bx++) {
      const b = by * bw + bx;
      const fill = WORDS[state[b]];
      for (let py = 0; py < zoom; py++)
        for (let px = 0; px < zoom; px++) {
          const mark = twice[b] && (zoom < 3 || (px >= lo && px < hi && py >= lo && py < hi));
          pixels[(by * zoom + py) * width + bx * zoom + px] = mark ? TWICE_WORD : fill;
        }
    }
  return { width, height, zoom, pixels };
}
