// Issue 17, item 3: the preview and its estimate follow every input of the plan (the full dose, the
// order), marked stale until the new plan is in; planning runs in a worker.
import { expect, test } from '@playwright/test';
import { drawFilledRectangle } from './draw';

const estimate = async (summary: import('@playwright/test').Locator) => /about (\d+:\d\d:\d\d)/.exec((await summary.textContent()) ?? '')?.[1];

test('changing the full dose or the order re-plans the preview without "Plan again"', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.43, 0.43]);
  await page.getByRole('tab', { name: 'Preview exposure' }).click();
  const summary = page.getByTestId('preview-summary');
  await expect(summary).toHaveAttribute('data-stale', 'false', { timeout: 20_000 });
  const at4ms = await estimate(summary);
  const canvasBefore = await page.getByTestId('preview-canvas').boundingBox();

  await page.getByLabel('Full dose').fill('1000');
  await expect(summary).toHaveAttribute('data-stale', 'false', { timeout: 20_000 });
  await expect.poll(() => estimate(summary), { timeout: 20_000 }).not.toBe(at4ms);
  const at1000ms = (await estimate(summary))!;
  const [h, m] = at1000ms.split(':').map(Number);
  expect(h * 60 + m).toBeGreaterThan(10); // a second a cell: far longer than at 4 ms
  expect(await page.getByTestId('preview-canvas').boundingBox()).toEqual(canvasBefore); // the stale note moved nothing
  await page.screenshot({ path: info.outputPath('full-dose-1000.png') });

  await page.getByLabel('Order').selectOption('random');
  await expect.poll(() => estimate(summary), { timeout: 20_000 }).not.toBe(at1000ms);
  await expect(summary).toHaveAttribute('data-stale', 'false');
  await page.screenshot({ path: info.outputPath('order-random.png') });
});

test('while a new plan is on its way, the old one is marked stale', async ({ page }) => {
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.43, 0.43]);
  await page.getByRole('tab', { name: 'Preview exposure' }).click();
  const summary = page.getByTestId('preview-summary');
  await expect(summary).toHaveAttribute('data-stale', 'false', { timeout: 20_000 });
  // The plan waits 200 ms after the last change: right after the change the shown one is stale.
  await page.getByLabel('Full dose').fill('7');
  await expect(page.getByRole('status').filter({ hasText: 'Changed since this plan' })).toBeVisible();
  await expect(summary).toHaveAttribute('data-stale', 'false', { timeout: 20_000 });
  await expect(page.getByRole('status').filter({ hasText: 'Changed since this plan' })).toBeHidden();
});
