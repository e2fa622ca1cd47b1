// E1: the grid editor's frame time while panning a full 4096² grid in Chromium, at three zooms,
// against a baseline drawn in the same page: one blit of a canvas-sized image, the least any
// frame costs. Frame time is the main thread's drawing work (what a frame's 16 ms must hold);
// the page's clock ticks in 0.1 ms. Also the app's size, gzipped: its first load against the 60 KB
// budget, and what loads on demand.
import { chromium } from '@playwright/test';
import { createReadStream, existsSync, statSync } from 'node:fs';
import { createServer } from 'node:http';
import { extname, join } from 'node:path';
import { bundleSize, formatBundleSize } from '../scripts/bundle-size';

const DIST = join(import.meta.dirname, '..', 'dist', 'app');
const TYPES: Record<string, string> = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.svg': 'image/svg+xml', '.wasm': 'application/wasm' };

/** The built app over HTTP on a free port (B4 serves it too). */
export function serve(): Promise<{ url: string; close: () => void }> {
  const server = createServer((req, res) => {
    const path = join(DIST, (req.url ?? '/').split('?')[0].replace(/\/$/, '/index.html'));
    if (!path.startsWith(DIST) || !existsSync(path) || statSync(path).isDirectory()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'content-type': TYPES[extname(path)] ?? 'application/octet-stream' });
    createReadStream(path).pipe(res);
  });
  return new Promise((resolve) =>
    server.listen(0, '127.0.0.1', () => {
      const { port } = server.address() as { port: number };
      resolve({ url: `http://127.0.0.1:${port}`, close: () => server.close() });
    }),
  );
}

export async function editorBench(): Promise<void> {
  if (!existsSync(join(DIST, 'index.html'))) throw new Error('build the app first: npm run build');
  const { url, close } = await serve();
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', args: ['--no-sandbox'] });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    // tsx keeps function names with an `__name` helper that the page lacks.
    await page.addInitScript('window.__name = (f) => f');
    await page.goto(`${url}/?bench&bed=204.8x204.8`); // 4096 × 4096 cells of 50 µm
    await page.waitForFunction(() => (window as unknown as { __studio?: unknown }).__studio);
    await page.getByTestId('editor-canvas').waitFor(); // the studio's chunk loads as it mounts, a task after the first screen
    const rows = await page.evaluate(async () => {
      type Ed = { grid: { cols: number; rows: number }; view: { scale: number; x: number; y: number }; pan(dx: number, dy: number): void;
        place(d: Uint8Array, w: number, h: number, x: number, y: number, label: string): void; fitTo(w: number, h: number): void; screen: { width: number; height: number } };
      const ed = (window as unknown as { __studio: Ed }).__studio;
      const w = window as unknown as { __editorFrameMs?: number };
      const n = ed.grid.cols * ed.grid.rows;
      // A busy picture: random doses in every cell, so no tile is empty.
      const doses = new Uint8Array(n);
      let s = 12345;
      for (let i = 0; i < n; i++) {
        s ^= s << 13, s ^= s >>> 17, s ^= s << 5;
        doses[i] = s & 255;
      }
      ed.place(doses, ed.grid.cols, ed.grid.rows, 0, 0, 'bench');
      const frame = () => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
      const canvas = document.querySelector('[data-testid="editor-canvas"]') as HTMLCanvasElement;
      const blitFrom = new OffscreenCanvas(canvas.width, canvas.height);
      blitFrom.getContext('2d')!.fillRect(0, 0, 10, 10);
      const ctx = canvas.getContext('2d')!;
      const median = (a: number[]) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];
      const out: { zoom: string; median: number; worst: number; baseline: number }[] = [];
      for (const [zoom, scale] of [['whole bed', 0], ['1 px a cell', 1], ['8 px a cell', 8]] as const) {
        ed.fitTo(ed.screen.width, ed.screen.height);
        if (scale) ed.view = { scale, x: 1000, y: 1000 };
        await frame();
        const times: number[] = [], base: number[] = [];
        for (let i = 0; i < 60; i++) {
          ed.pan(37, 23);
          await frame();
          times.push(w.__editorFrameMs ?? NaN);
          const t0 = performance.now();
          for (let k = 0; k < 20; k++) ctx.drawImage(blitFrom, 0, 0); // 20: the page's clock ticks in 0.1 ms
          base.push((performance.now() - t0) / 20);
        }
        out.push({ zoom, median: median(times), worst: Math.max(...times), baseline: Math.max(median(base), 0.005) });
      }
      return out;
    });
    console.log('\nE1 the grid editor panning a 4096 × 4096 grid of random doses in Chromium (budget 16 ms a frame; ratio = median / one canvas blit)');
    for (const r of rows) {
      console.log(`  ${r.zoom.padEnd(14)} median ${r.median.toFixed(2).padStart(6)} ms   worst ${r.worst.toFixed(2).padStart(6)} ms   ${(r.median / r.baseline).toFixed(1).padStart(6)}x   ${r.worst <= 16 ? 'within budget' : 'OVER BUDGET'}`);
    }
  } finally {
    await browser.close();
    close();
  }
  console.log(`\nB2 the app, gzipped as the ESP serves it (the budget holds the first load; see docs/app.md "Size"):\n${formatBundleSize(bundleSize(DIST))
    .split('\n').map((l) => `  ${l}`).join('\n')}`);
}
