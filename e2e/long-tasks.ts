// Test-only: the page's longest main-thread task while something runs, from a `longtask`
// PerformanceObserver (Chromium reports every task over 50 ms), and a large PNG made in Node.
import type { Page } from '@playwright/test';
import { deflateSync } from 'node:zlib';

/** Starts recording long tasks in the page; `stop()` returns the longest one's duration in ms (0: none over 50 ms). */
export async function watchLongTasks(page: Page): Promise<{ stop: () => Promise<{ longestMs: number; count: number }> }> {
  await page.evaluate(() => {
    const w = window as unknown as { __longTasks: number[]; __longObserver?: PerformanceObserver };
    w.__longObserver?.disconnect();
    w.__longTasks = [];
    w.__longObserver = new PerformanceObserver((list) => {
      for (const e of list.getEntries()) w.__longTasks.push(e.duration);
    });
    w.__longObserver.observe({ entryTypes: ['longtask'] });
  });
  return {
    stop: () =>
      page.evaluate(async () => {
        await new Promise((r) => setTimeout(r, 100)); // entries are delivered after their task
        const w = window as unknown as { __longTasks: number[]; __longObserver?: PerformanceObserver };
        w.__longObserver?.disconnect();
        return { longestMs: Math.round(Math.max(0, ...w.__longTasks)), count: w.__longTasks.length };
      }),
  };
}

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(bytes: Uint8Array): number {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 255] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}
function chunk(type: string, data: Uint8Array): Buffer {
  const body = Buffer.concat([Buffer.from(type, 'latin1'), data]);
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  body.copy(out, 4);
  out.writeUInt32BE(crc32(body), 8 + data.length);
  return out;
}

/** A grey PNG of w × h pixels (a checker of `square` px with a gradient), at `dpi` stated in its pHYs. */
export function greyPng(w: number, h: number, dpi: number, square = 64): Buffer {
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(w, 0);
  ihdr.writeUInt32BE(h, 4);
  ihdr[8] = 8; // bit depth
  ihdr[9] = 0; // greyscale
  const raw = Buffer.alloc((w + 1) * h);
  for (let y = 0; y < h; y++) {
    const row = y * (w + 1);
    for (let x = 0; x < w; x++) raw[row + 1 + x] = ((x / square) ^ (y / square)) & 1 ? 255 : (x * 255) / w;
  }
  const phys = Buffer.alloc(9);
  const ppm = Math.round(dpi / 0.0254);
  phys.writeUInt32BE(ppm, 0);
  phys.writeUInt32BE(ppm, 4);
  phys[8] = 1;
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr), chunk('pHYs', phys), chunk('IDAT', deflateSync(raw, { level: 1 })), chunk('IEND', new Uint8Array(0))]);
}
