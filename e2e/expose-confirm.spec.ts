// Issue 17, item 4: before any LED fires, the user sees the estimated time, where on the bed the job
// lands and the dry run's verdict, and agrees once. The test pattern follows the full-dose field.
// A move that needs homing says so first.
import { expect, test } from '@playwright/test';
import { drawFilledRectangle } from './draw';

test('"Expose test pattern" asks first: its time at the full dose set, where it lands, the dry run', async ({ page }, info) => {
  test.setTimeout(90_000); // it uploads and starts a job at the end
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByLabel('Full dose').fill('8');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the test pattern?' });
  await expect(dialog).toBeVisible();
  await expect(dialog).toContainText(/About \d:\d\d:\d\d of exposing, at a full dose of 8 ms\./);
  await expect(dialog).toContainText('It lands at X 20–24.8 mm, Y 20–23.2 mm on the bed (4.8 × 3.2 mm). The head homes first.');
  await expect(dialog.getByRole('listitem')).toHaveCount(5); // machine, envelope, mesh, dose, thermal
  await expect(dialog.getByText(/^dose: the longest exposure is 8\.0 ms$/)).toBeVisible(); // the field, not a fixed 4 ms
  await dialog.screenshot({ path: info.outputPath('test-pattern-question.png') });
  // Nothing has fired or moved while the question is open.
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'idle');
  await expect(page.getByRole('region', { name: 'Console' }).getByText('> G28')).toHaveCount(0);
  await dialog.getByRole('button', { name: 'Cancel' }).click();
  await expect(dialog).toBeHidden();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'idle');
  // Agreed, it runs.
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await dialog.getByRole('button', { name: 'Expose now' }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
});

test('"Expose drawing" asks with the estimate, the drawing\'s place on the bed and the verdict', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.45, 0.45]);
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  await expect(dialog).toContainText(/About \d:\d\d:\d\d of exposing, at a full dose of 4 ms\./);
  await expect(dialog).toContainText(/It lands at X [\d.]+–[\d.]+ mm, Y [\d.]+–[\d.]+ mm on the bed/);
  await expect(dialog.locator('li[data-level="ok"]')).toHaveCount(6); // machine, envelope, clipping, mesh, dose, thermal
  await page.screenshot({ path: info.outputPath('drawing-question.png') });
  await dialog.getByRole('button', { name: 'Cancel' }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'idle');
});

test('Go to on a machine that is not homed says it will home first, and homes only on a yes', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByRole('tab', { name: 'Position' }).click();
  await page.getByRole('button', { name: 'Go', exact: true }).click();
  const dialog = page.getByRole('dialog', { name: 'Go to: home the machine first?' });
  await expect(dialog).toContainText('The machine is not homed. Homing moves every axis to its endstop');
  await dialog.screenshot({ path: info.outputPath('home-first.png') });
  const log = page.getByRole('region', { name: 'Console' });
  await expect(log.getByText('> G28')).toHaveCount(0);
  await dialog.getByRole('button', { name: 'Home and continue' }).click();
  await expect(log.getByText('> G28')).toHaveCount(1);
  await expect(page.getByTestId('position')).toContainText('X 100.000 Y 100.000', { timeout: 30_000 });
  // Homed now: the next Go to goes without asking.
  await page.getByTestId('goto-x').fill('50');
  await page.getByRole('button', { name: 'Go', exact: true }).click();
  await expect(page.getByTestId('position')).toContainText('X 50.000', { timeout: 30_000 });
  await expect(page.getByRole('dialog')).toHaveCount(0);
});
