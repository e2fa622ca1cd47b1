// Issue 17, items 1 and 2: the dry run's thermal forecast is the simulated printer's, a job that would
// pause at a soft limit is offered paced with its time, and a thermal pause says how to go on.
import { expect, test, type Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';

async function hotDrawing(page: Page): Promise<void> {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.412, 0.412]); // about 2.4 × 2.4 mm, every cell at full dose
  await page.getByLabel('Full dose').fill('800');
  await page.getByRole('button', { name: 'Expose drawing' }).click();
}

test('a job that would pause to cool is offered paced, with its time, and runs through without a pause', async ({ page }, info) => {
  test.setTimeout(120_000);
  await hotDrawing(page);
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  await expect(dialog.locator('li[data-level="warning"]')).toContainText(
    /thermal: T4 would reach its 50 °C soft limit \d:\d\d:\d\d in, at stop \d+ of \d+: the job would pause there to cool\. Paced, it waits \d:\d\d:\d\d in all to cool, takes about \d:\d\d:\d\d/,
  );
  await expect(dialog.getByTestId('paced-offer')).toContainText(/about \d:\d\d:\d\d in all, with no pause/);
  await dialog.screenshot({ path: info.outputPath('paced-offer.png') });
  await dialog.getByRole('button', { name: 'Expose paced' }).click();
  const state = page.getByTestId('job-state');
  await expect(state).toContainText('running, paced', { timeout: 30_000 });
  await expect(state).toContainText('waiting for the head to cool', { timeout: 60_000 });
  await page.screenshot({ path: info.outputPath('cooling.png') });
  await expect(state).toHaveAttribute('data-state', 'done', { timeout: 90_000 });
  await expect(page.getByRole('region', { name: 'Console' })).not.toContainText('soft limit');
});

test('a job run unpaced pauses at the soft limit, says why, and continues paced once the head has cooled', async ({ page }, info) => {
  test.setTimeout(120_000);
  await hotDrawing(page);
  await page.getByRole('dialog', { name: 'Expose the drawing?' }).getByRole('button', { name: 'Expose anyway' }).click();
  const hint = page.getByTestId('cool-hint');
  await expect(hint).toContainText('Paused to cool: the head reached a soft limit', { timeout: 60_000 });
  await expect(page.getByTestId('job-state')).toContainText('paused (overtemp)');
  await page.screenshot({ path: info.outputPath('paused-to-cool.png') });
  const go = hint.getByRole('button', { name: 'Continue paced' });
  await expect(go).toBeEnabled(); // while the head is still hot: the printer waits for it to cool first
  await go.click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 90_000 });
  await expect(hint).toBeHidden();
});
