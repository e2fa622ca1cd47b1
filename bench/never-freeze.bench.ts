// B4: the page's longest main-thread task (a `longtask` observer; budget 50 ms) while each piece of
// heavy work runs in the built app in Chromium, driven as a person drives it, against the same work
// timed on one thread: what the page's thread carried before it moved to the work worker
// (app/src/work/). The dry run, the board and the preview are timed in Node; the picture's decoding
// in the page (drawn, read back, made grey and averaged into cells, as studio/image/ did).
import { chromium, type Page } from '@playwright/test';
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { cpus, loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { boardArtwork, boardSrc } from '../app/src/pcb';
import { busyBoard } from '../app/src/pcb/test-boards';
import { headerOf } from '../app/src/planner/job-header';
import { fastestOrder, orderEstimates } from '../app/src/planner/job-plan';
import { previewGrid } from '../app/src/preview/exposure-preview';
import { planJob } from '../app/src/preview/plan-work';
import { scanPreviewGrid } from '../app/src/preview/scan-preview';
import { dryRun } from '../app/src/studio/dry-run';
import { DoseGrid } from '../app/src/studio/grid/grid';
import { jobFromGrid } from '../app/src/studio/grid-job';
import { DEFAULT_CONFIG, bedOf, ledsOf, motionOf } from '../app/src/studio/machine-config';
import { drawFilledRectangle } from '../e2e/draw';
import { greyPng, watchLongTasks } from '../e2e/long-tasks';
import { serve } from './editor.bench';

const DIST = join(import.meta.dirname, '..', 'dist', 'app');
const IMPORT = /^Import artwork \(SVG, PNG, JPG, BMP, GIF\)/;

function timed(run: () => unknown): number {
  const t0 = performance.now();
  run();
  return performance.now() - t0;
}

/** The same work on one thread, ms: what the page's thread did before. */
function oneThread(): Record<'dryRun' | 'preview' | 'board', number> {
  const bed = bedOf(DEFAULT_CONFIG);
  const cols = Math.round((bed.bedMm.x * 1000) / bed.pitchUm.x), rows = Math.round((bed.bedMm.y * 1000) / bed.pitchUm.y);
  const job = jobFromGrid(new DoseGrid(cols, rows, new Uint8Array(cols * rows).fill(255)), bed, { dose: { map: 'linear', fullUs: 4000 }, strategy: { name: 'serpentine' }, leds: ledsOf(DEFAULT_CONFIG) })!;
  const machine = motionOf(DEFAULT_CONFIG);
  const dryRunMs = timed(() => {
    const orders = orderEstimates({ header: headerOf(job), cells: job.gridData }, machine);
    dryRun({ ...job, strategy: { name: fastestOrder(orders) } }, DEFAULT_CONFIG, { leveling: false, startC: null, cuts: [] });
  });
  // The preview planned in a worker already: the page binned the plan's light for the canvas.
  const p = planJob({ job, machine, auto: true });
  const planned = { ...job, strategy: { name: p.order } };
  const previewMs = timed(() => (p.scan ? scanPreviewGrid(planned, p.scan.doses, p.plan.count) : previewGrid(planned, p.plan, p.plan.count)));
  const src = boardSrc([{ name: 'busy-F_Cu.gbr', text: busyBoard() }]);
  const boardMs = timed(() => {
    const b = boardArtwork(src);
    const w = Math.round((b.windowMm.x1 - b.windowMm.x0) * 20), h = Math.round((b.windowMm.y1 - b.windowMm.y0) * 20); // 50 µm cells
    b.cover(w, h, { layers: [{ kind: 'copper-top', expose: true }], drillClear: 'none', marks: [] });
  });
  return { dryRun: dryRunMs, preview: previewMs, board: boardMs };
}

/** A 36-megapixel picture's decoding as the page did it: drawn, read back, grey, checked for line art, averaged into cells. */
async function pictureOnThePage(page: Page, path: string): Promise<number> {
  return page.evaluate(async (bytes) => {
    const blob = new Blob([Uint8Array.from(atob(bytes), (c) => c.charCodeAt(0))], { type: 'image/png' });
    const bitmap = await createImageBitmap(blob);
    const t0 = performance.now();
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const ctx = canvas.getContext('2d')!;
    ctx.drawImage(bitmap, 0, 0);
    const rgba = ctx.getImageData(0, 0, bitmap.width, bitmap.height).data;
    const grey = new Uint8Array(bitmap.width * bitmap.height);
    let mid = 0;
    for (let i = 0, p = 0; i < grey.length; i++, p += 4) {
      const a = rgba[p + 3] / 255;
      grey[i] = Math.round((0.2126 * rgba[p] + 0.7152 * rgba[p + 1] + 0.0722 * rgba[p + 2]) * a + 255 * (1 - a));
      if (grey[i] > 24 && grey[i] < 231) mid++;
    }
    const side = 3048, s = bitmap.width / side, cells = new Uint8Array(side * side); // 152.4 mm at 50 µm
    for (let y = 0; y < side; y++)
      for (let x = 0; x < side; x++) {
        let sum = 0, n = 0;
        for (let py = Math.floor(y * s); py < Math.ceil((y + 1) * s); py++) for (let px = Math.floor(x * s); px < Math.ceil((x + 1) * s); px++) (sum += grey[py * bitmap.width + px]), n++;
        cells[y * side + x] = sum / n;
      }
    return performance.now() - t0 + (mid > grey.length ? 1 : 0);
  }, readFileSync(path).toString('base64'));
}

export async function neverFreezeBench(): Promise<void> {
  if (!existsSync(join(DIST, 'index.html'))) throw new Error('build the app first: npm run build');
  const loadAtStart = loadavg()[0];
  const dir = mkdtempSync(join(tmpdir(), 'uv-bench-'));
  const png = join(dir, 'big.png'), gbr = join(dir, 'busy-F_Cu.gbr'), small = join(dir, 'small.png');
  writeFileSync(png, greyPng(6000, 6000, 1000));
  writeFileSync(small, greyPng(400, 300, 300));
  writeFileSync(gbr, busyBoard());
  const before = oneThread();
  const { url, close } = await serve();
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', args: ['--no-sandbox'] });
  const rows: { what: string; longest: number; before?: number; where?: string }[] = [];
  try {
    // Each case in a fresh context: nothing autosaved by the one before it is restored.
    let page: Page = null as unknown as Page;
    const studio = async () => {
      await page?.context().close();
      page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
      await page.addInitScript('window.__name = (f) => f'); // tsx keeps function names with an `__name` helper that the page lacks
      await page.goto(url);
      await page.getByTestId('connection').and(page.locator('[data-state="connected"]')).waitFor({ timeout: 30_000 });
    };
    const whole = () => drawFilledRectangle(page, [0.001, 0.001], [0.999, 0.999]);
    let watch: Awaited<ReturnType<typeof watchLongTasks>>;

    // The page's load, from its first script (a buffered observer) until connected and the thermal chart drawn.
    page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
    await page.addInitScript('window.__name = (f) => f');
    await page.addInitScript(() => {
      const w = window as unknown as { __loadTasks: number[] };
      w.__loadTasks = [];
      new PerformanceObserver((list) => list.getEntries().forEach((e) => w.__loadTasks.push(e.duration))).observe({ type: 'longtask', buffered: true });
    });
    await page.goto(url);
    await page.getByTestId('connection').and(page.locator('[data-state="connected"]')).waitFor({ timeout: 30_000 });
    await page.getByTestId('thermal-chart').locator('canvas').waitFor({ timeout: 30_000 });
    await page.waitForTimeout(1000);
    rows.push({ what: 'page load (until connected, the chart drawn)', longest: await page.evaluate(() => Math.round(Math.max(0, ...(window as unknown as { __loadTasks: number[] }).__loadTasks))) });

    // A small picture imported, and autosaved a second later.
    await studio();
    watch = await watchLongTasks(page);
    await page.getByLabel(IMPORT).setInputFiles(small);
    await page.getByRole('region', { name: 'Selected object' }).getByText('small.png').waitFor({ timeout: 30_000 });
    await page.waitForTimeout(2500);
    rows.push({ what: 'small PNG (400 x 300 px), placed and autosaved', longest: (await watch.stop()).longestMs });

    // The whole bed filled with a rectangle, drawn as a person draws it, and autosaved.
    await studio();
    watch = await watchLongTasks(page);
    await whole();
    await page.waitForTimeout(2500);
    rows.push({ what: 'whole-bed filled rectangle, drawn and autosaved', longest: (await watch.stop()).longestMs });

    await studio();
    await whole();
    watch = await watchLongTasks(page);
    await page.getByRole('button', { name: 'Expose drawing' }).click();
    await page.getByRole('dialog', { name: 'Expose the drawing?' }).getByText(/of exposing/).waitFor({ timeout: 120_000 });
    rows.push({ what: 'whole-bed dry run (4000 x 4000 cells)', longest: (await watch.stop()).longestMs, before: before.dryRun, where: 'Node' });

    await studio();
    const pictureMs = await pictureOnThePage(page, png);
    watch = await watchLongTasks(page);
    await page.getByLabel(IMPORT).setInputFiles(png);
    await page.getByRole('region', { name: 'Selected object' }).getByText('big.png').waitFor({ timeout: 120_000 });
    await page.waitForTimeout(3000); // its raster and sprite, drawn in the worker
    rows.push({ what: '36-megapixel PNG, read and placed', longest: (await watch.stop()).longestMs, before: pictureMs, where: 'page' });

    await studio();
    watch = await watchLongTasks(page);
    await page.getByLabel(IMPORT).setInputFiles(gbr);
    await page.getByRole('region', { name: 'Selected object' }).getByText('busy').first().waitFor({ timeout: 120_000 });
    await page.waitForTimeout(1000);
    await page.getByRole('button', { name: 'Expose drawing' }).click();
    await page.getByRole('dialog', { name: 'Expose the drawing?' }).getByText(/of exposing/).waitFor({ timeout: 120_000 });
    rows.push({ what: 'busy 100 x 80 mm Gerber, imported and exposed', longest: (await watch.stop()).longestMs, before: before.board, where: 'Node' });

    await studio();
    await whole();
    watch = await watchLongTasks(page);
    await page.getByTestId('view-preview').click();
    await page.getByTestId('preview-summary').getByText(/about/).waitFor({ timeout: 120_000 });
    await page.waitForTimeout(500);
    rows.push({ what: 'whole-bed preview (its light binned for the canvas)', longest: (await watch.stop()).longestMs, before: before.preview, where: 'Node' });
  } finally {
    await browser.close();
    close();
  }
  console.log(`\nB4 at a load of ${loadAtStart.toFixed(1)} → ${loadavg()[0].toFixed(1)} (1-minute average at its start and end, ${cpus().length} cores): the page's longest task while heavy work runs, built app in Chromium (longtask observer; budget 50 ms), against the same work on one thread`);
  for (const r of rows)
    console.log(`  ${r.what.padEnd(52)} longest task ${String(r.longest).padStart(4)} ms   ${r.longest <= 50 ? 'within budget' : 'OVER BUDGET'}${r.before === undefined ? '' : `   on one thread (${r.where}): ${r.before.toFixed(0).padStart(5)} ms`}`);
}
