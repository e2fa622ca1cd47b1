// Issue 19, exposure on the move: a drawing exposed as a scan job on the simulated printer. The
// preview shows its passes, the dry run says it is a scan job, and it runs in the time estimated.
import { expect, test } from '@playwright/test';
import { drawFilledRectangle } from './draw';

test('a drawing exposed as a scan job: passes in the preview, scan in the dry run, done in the estimated time', async ({ page }, info) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  // A 40 % gray block: its LEDs are lit 40 % of each window, so the head stays within its limits.
  await page.getByTestId('tool-dose').fill('102');
  await drawFilledRectangle(page, [0.4, 0.4], [0.408, 0.44]);
  await page.getByTestId('full-ms').fill('40'); // a 40 ms window: the job runs for a minute or more of printer time
  await page.getByTestId('strategy').selectOption('scan');

  await page.getByTestId('view-preview').click();
  const summary = page.getByTestId('preview-summary');
  await expect(summary).toContainText(/^Scan \(on the move\): (\d+) passes at 1\.25 mm\/s, a 40\.00 ms window per cell, about \d:\d\d:\d\d, \d+ mm of travel$/);
  const passes = Number(/: (\d+) passes/.exec((await summary.textContent())!)![1]);
  expect(passes).toBeGreaterThan(1);
  await expect(page.getByTestId('preview-at')).toContainText(`${passes} of ${passes} passes`);
  await page.screenshot({ path: info.outputPath('scan-preview.png'), fullPage: true });

  await page.getByTestId('view-draw').click();
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  await expect(dialog.getByTestId('dry-run')).toContainText(`mode: scan job (on the move): ${passes} passes at 1.25 mm/s, a 40.00 ms window per cell`);
  const estimate = /About (\d+):(\d\d):(\d\d) of exposing/.exec((await dialog.getByTestId('confirm-estimate').textContent())!)!;
  const estimateS = Number(estimate[1]) * 3600 + Number(estimate[2]) * 60 + Number(estimate[3]);
  expect(estimateS).toBeGreaterThan(50); // long enough that whole seconds judge 2 %
  await page.screenshot({ path: info.outputPath('scan-dry-run.png') });
  await expect(dialog.locator('li[data-level="error"], li[data-level="warning"]')).toHaveCount(0);
  await dialog.getByRole('button', { name: 'Expose now' }).click();

  await expect(page.getByTestId('job-state')).toContainText(new RegExp(`running: pass \\d+ of ${passes}`), { timeout: 30_000 });
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 90_000 });
  await expect(page.getByTestId('job-state')).toContainText(`done: pass ${passes} of ${passes}`);
  const took = page.getByTestId('job-took');
  const elapsedS = Number(await took.getAttribute('data-elapsed-s'));
  const estimateUs = Number(await took.getAttribute('data-estimate-us'));
  expect(Math.abs(estimateUs / 1e6 - estimateS)).toBeLessThanOrEqual(0.5); // the estimate shown is the one kept
  // The printer reports whole seconds, floored: within 2 % of the estimate, with that second's grace.
  expect(Math.abs(elapsedS - estimateUs / 1e6)).toBeLessThanOrEqual(0.02 * (estimateUs / 1e6) + 1);
  await page.screenshot({ path: info.outputPath('scan-done.png'), fullPage: true });
});
