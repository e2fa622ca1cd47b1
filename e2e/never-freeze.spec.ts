// Issue 29 item 6: the page never freezes. The heavy work (the dry run, a 36-megapixel picture,
// a busy Gerber board read and exposed, a whole bed's preview) runs in a worker and reaches its
// result; the page's longest task from the click to the result (a `longtask` observer) is printed
// and annotated here, and judged against its 50 ms budget by the B4 bench (`npm run bench`), since
// a speed target is a benchmark's, never a timed test's: on this 2-core machine the same case moved
// by 60 ms from run to run with the load (docs/app.md, B4).
import { expect, test, type Page } from '@playwright/test';
import { writeFileSync } from 'node:fs';
import { busyBoard } from '../app/src/pcb/test-boards';
import { drawFilledRectangle } from './draw';
import { greyPng, watchLongTasks } from './long-tasks';

const IMPORT = /^Import artwork \(SVG, PNG, JPG, BMP, GIF\)/;

async function studio(page: Page) {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected', { timeout: 20_000 });
}

/** The whole bed painted: a filled rectangle from corner to corner of the canvas, clipped to the bed. */
const paintWholeBed = (page: Page) => drawFilledRectangle(page, [0.001, 0.001], [0.999, 0.999]);

function report(what: string, r: { longestMs: number; count: number }) {
  console.log(`[longtask] ${what}: longest ${r.longestMs} ms, ${r.count} over 50 ms`);
  test.info().annotations.push({ type: 'longest task', description: `${what}: ${r.longestMs} ms` });
}

test('a whole-bed dry run: the question comes, the page’s longest task printed', async ({ page }, info) => {
  test.setTimeout(120_000);
  await studio(page);
  await paintWholeBed(page);
  const watch = await watchLongTasks(page);
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  await expect(dialog).toContainText(/About \d+:\d\d:\d\d of exposing/, { timeout: 60_000 });
  const r = await watch.stop();
  report('whole-bed dry run', r);
  await page.screenshot({ path: info.outputPath('dry-run.png') });
});

test('a 36-megapixel PNG: read and placed, the page’s longest task printed', async ({ page }, info) => {
  test.setTimeout(120_000);
  await studio(page);
  // 152.4 mm square at 1000 DPI; picked from a file, as a person picks it (a buffer would be decoded in the page by the test itself)
  const path = info.outputPath('big.png');
  writeFileSync(path, greyPng(6000, 6000, 1000));
  const watch = await watchLongTasks(page);
  await page.getByLabel(IMPORT).setInputFiles(path);
  await expect(page.getByRole('region', { name: 'Selected object' })).toContainText('big.png', { timeout: 60_000 });
  await page.waitForTimeout(3000); // its raster drawn in the worker, then on the canvas
  const r = await watch.stop();
  report('36-megapixel PNG', r);
  await page.screenshot({ path: info.outputPath('big-png.png') });
});

test('a busy 100 × 80 mm Gerber board: imported and exposed, the page’s longest tasks printed', async ({ page }, info) => {
  test.setTimeout(120_000);
  await studio(page);
  const path = info.outputPath('busy-F_Cu.gbr'); // 41 600 shapes; picked from a file, as the PNG is
  writeFileSync(path, busyBoard());
  const watch = await watchLongTasks(page);
  await page.getByLabel(IMPORT).setInputFiles(path);
  await expect(page.getByRole('region', { name: 'Selected object' })).toContainText('busy', { timeout: 60_000 });
  await page.waitForTimeout(500);
  const imported = await watch.stop();
  report('busy Gerber board, import', imported);
  await page.screenshot({ path: info.outputPath('busy-board.png') });
  const watch2 = await watchLongTasks(page);
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await expect(page.getByRole('dialog', { name: 'Expose the drawing?' })).toContainText(/About \d+:\d\d:\d\d of exposing/, { timeout: 60_000 });
  const exposed = await watch2.stop();
  report('busy Gerber board, expose', exposed);
  await page.screenshot({ path: info.outputPath('busy-board-question.png') });
});

test('a whole-bed preview: shown, the page’s longest task printed', async ({ page }, info) => {
  test.setTimeout(120_000);
  await studio(page);
  await paintWholeBed(page);
  const watch = await watchLongTasks(page);
  await page.getByTestId('view-preview').click();
  await expect(page.getByTestId('preview-summary')).toContainText(/about \d+:\d\d:\d\d/, { timeout: 60_000 });
  await page.waitForTimeout(300);
  const r = await watch.stop();
  report('whole-bed preview', r);
  await page.screenshot({ path: info.outputPath('preview.png') });
});

test('what takes over a second says how far it has got and can be cancelled: the dry run, an import, the preview', async ({ page }, info) => {
  test.setTimeout(120_000);
  await studio(page);
  await paintWholeBed(page);

  // The dry run: its stage shown beside the job's controls; cancelled, no question follows.
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const checking = page.getByRole('status', { name: 'Checking the drawing' });
  await expect(checking).toContainText(/Checking the drawing: (starting|choosing the fastest order|planning|forecasting the heat)/);
  await page.screenshot({ path: info.outputPath('dry-run-progress.png') });
  await checking.getByRole('button', { name: 'Cancel' }).click();
  await expect(checking).toBeHidden();
  await page.waitForTimeout(500);
  await expect(page.getByRole('dialog', { name: 'Expose the drawing?' })).toBeHidden();
  await expect(page.getByTestId('action-error')).toHaveCount(0);

  // A 36-megapixel picture being read: cancelled, nothing is placed.
  const path = info.outputPath('big.png');
  writeFileSync(path, greyPng(6000, 6000, 1000));
  await page.getByLabel(IMPORT).setInputFiles(path);
  const reading = page.getByRole('status', { name: 'Reading big.png' });
  await expect(reading).toContainText(/big\.png: (reading the file|decoding the picture)/);
  await reading.screenshot({ path: info.outputPath('import-progress.png') });
  await reading.getByRole('button', { name: 'Cancel' }).click();
  await expect(reading).toBeHidden();
  await expect(page.getByRole('region', { name: 'Selected object' })).toHaveCount(0);

  // The whole bed's preview: planning, cancelled, planned again on request.
  await page.getByTestId('view-preview').click();
  const planning = page.getByRole('status').filter({ hasText: 'Planning…' });
  await expect(planning).toBeVisible();
  await planning.getByRole('button', { name: 'Cancel' }).click();
  await expect(page.getByText('Planning cancelled')).toBeVisible();
  await page.getByRole('button', { name: 'Plan again' }).click();
  await expect(page.getByTestId('preview-summary')).toContainText(/about \d+:\d\d:\d\d/, { timeout: 60_000 });
  await page.screenshot({ path: info.outputPath('preview-again.png') });
});
