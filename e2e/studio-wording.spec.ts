// Issue 41 item 6: the studio's words, each said once and in its unit: the preview names the fastest
// order once, a scan too slow for the printer says why instead of "0 of 0 passes".
import { expect, test } from '@playwright/test';
import { drawFilledRectangle } from './draw';

test('the preview names the fastest order once', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.5, 0.46]); // a filled block: automatic picks scan
  await page.getByTestId('view-preview').click();
  const summary = page.getByTestId('preview-summary');
  await expect(summary).toContainText(/^The fastest order, Scan \(on the move\): \d+ passes at [\d.]+ mm\/s/, { timeout: 30_000 });
  await expect(summary).not.toContainText('Scan (on the move): Scan');
  await page.screenshot({ path: info.outputPath('fastest-order.png'), fullPage: true });
});

test('a scan the printer cannot run says why and what to do, with no empty canvas and no "0 of 0 passes"', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.5, 0.46]);
  await page.getByTestId('full-ms').fill('1000'); // a 1 s window: slower than the step engine can step
  await page.getByTestId('strategy').selectOption('scan');
  await page.getByTestId('view-preview').click();
  await expect(page.getByTestId('preview-summary')).toHaveText(/^Scan \(on the move\): the printer cannot run it: the scan speed 0\.050 mm\/s/, { timeout: 30_000 });
  await expect(page.getByRole('alert')).toHaveText(/^Pick another order/);
  await expect(page.getByTestId('preview-canvas')).toHaveCount(0);
  await expect(page.getByTestId('preview-at')).toHaveCount(0);
  await page.screenshot({ path: info.outputPath('scan-refused.png'), fullPage: true });
  // Automatic takes an order the printer can run, and the preview is back.
  await page.getByTestId('strategy').selectOption('auto');
  await expect(page.getByTestId('preview-at')).toHaveText(/^\d+ of [1-9]\d* (stops|passes)/, { timeout: 30_000 });
  await expect(page.getByTestId('preview-canvas')).toBeVisible();
});

test('a job that has just started says it is on its way to its first stop, never "stop 0 of"', async ({ page }, info) => {
  test.setTimeout(90_000);
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=4');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  // Every text the job's line shows, as it changes.
  await page.evaluate(() => {
    const seen: string[] = [];
    (window as unknown as { __jobTexts: string[] }).__jobTexts = seen;
    new MutationObserver(() => {
      const t = document.querySelector('[data-testid="job-state"] p')?.textContent?.trim();
      if (t && seen.at(-1) !== t) seen.push(t);
    }).observe(document.body, { subtree: true, childList: true, characterData: true });
  });
  await page.getByTestId('strategy').selectOption('serpentine');
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of \d+/, { timeout: 60_000 });
  await page.screenshot({ path: info.outputPath('running.png'), fullPage: true });
  const texts = await page.evaluate(() => (window as unknown as { __jobTexts: string[] }).__jobTexts);
  expect(texts.some((t) => /^running: on its way to the first of \d+ stops$/.test(t)), texts.join(' | ')).toBe(true);
  expect(texts.filter((t) => / 0 of /.test(t))).toEqual([]);
  await page.getByRole('button', { name: 'Stop', exact: true }).click();
});
