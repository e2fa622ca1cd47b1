// An SVG drawing as artwork: the browser draws it (an <img> runs no script and fetches nothing)
// into a canvas at up to four samples a cell each way, a band of rows at a time, and each cell's
// grey is the mean of its samples, so it is the share of the cell the drawing leaves bare.

import { resample, toGray, type Gray } from '../image/gray';
import { svgSize } from '../image/svg-size';
import type { Artwork } from './artwork';

/** Samples drawn in all, and in one band: a whole bed falls back to one sample a cell. */
const MAX_SAMPLES = 24_000_000;
const BAND_SAMPLES = 4_000_000;

export async function svgArtwork(src: string): Promise<Artwork> {
  const size = svgSize(await (await fetch(src)).text());
  const img = new Image();
  img.src = `data:image/svg+xml;charset=utf-8,${encodeURIComponent(size.renderable)}`;
  try {
    await img.decode();
  } catch {
    throw new Error('the browser could not draw this SVG');
  }
  return { pixels: { width: size.px.x, height: size.px.y }, cover: (w, h) => drawn(img, w, h) };
}

function drawn(img: HTMLImageElement, w: number, h: number): Gray {
  const s = Math.max(1, Math.min(4, Math.floor(Math.sqrt(MAX_SAMPLES / (w * h)))));
  const bandRows = Math.max(1, Math.min(h, Math.floor(BAND_SAMPLES / (w * s * s))));
  const canvas = new OffscreenCanvas(w * s, bandRows * s);
  const ctx = canvas.getContext('2d', { willReadFrequently: true })!;
  const values = new Uint8Array(w * h);
  for (let y0 = 0; y0 < h; y0 += bandRows) {
    const rows = Math.min(bandRows, h - y0);
    ctx.fillStyle = '#fff';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.drawImage(img, 0, -y0 * s, w * s, h * s);
    const band = toGray(ctx.getImageData(0, 0, w * s, rows * s).data, w * s, rows * s);
    values.set(resample(band, w, rows).values, y0 * w);
  }
  return { width: w, height: h, values };
}
