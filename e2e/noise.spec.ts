// Issue 17, items 13 and 14: what a newcomer takes for errors is gone, and the thermal chart reads
// like a dashboard (current values in its legend, time in minutes), on the printer's own clock.
import { expect, test } from '@playwright/test';

test('a page load asks for no /status and logs no errors; opening Probe & mesh shows no error the user did not cause', async ({ page }, info) => {
  const requests: string[] = [];
  const consoleErrors: string[] = [];
  page.on('request', (r) => requests.push(new URL(r.url()).pathname));
  page.on('console', (m) => (m.type() === 'error' || m.type() === 'warning') && consoleErrors.push(m.text()));
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByRole('tab', { name: 'Probe & mesh' }).click();
  await expect(page.getByText('No mesh yet: probe the bed.')).toBeVisible();
  // The mesh was asked for (M420 V) and the printer has none: an answer, not an error.
  const log = page.getByRole('region', { name: 'Console' }).getByRole('list');
  await expect(log.getByText('> M420 V')).toHaveCount(0); // the app's own question is not the user's line
  await page.waitForTimeout(500); // the answer has arrived well within this at 20×
  await expect(log.getByText(/E11/)).toHaveCount(0);
  await expect(page.getByTestId('action-error')).toHaveCount(0);
  expect(requests).not.toContain('/status');
  expect(consoleErrors).toEqual([]);
  await page.screenshot({ path: info.outputPath('probe-tab.png') });
  // Asked for on purpose, the debug view still shows the exchange.
  await page.getByLabel('debug').check();
  await expect(log.getByText(/echo:E11/)).toBeVisible();
});

test('at ?simSpeed=20 the thermal watch measures on the printer\'s clock: no false "rising" warning; one legend (the table of sensors) with the latest values, those under the cursor, and the axis minutes', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const chart = page.getByTestId('thermal-chart');
  // 90 reports: 90 s of the printer's time, three times the span the watch fits its slope over.
  await expect.poll(async () => Number(await chart.getAttribute('data-samples')), { timeout: 20_000 }).toBeGreaterThanOrEqual(90);
  await expect(page.getByTestId('thermal-warning')).toHaveCount(0);
  // One legend, the table of sensors: the latest readings while the cursor is away.
  await expect(chart.locator('.u-legend')).toHaveCount(0);
  const at = page.getByTestId('temperatures-at');
  await expect(at).toHaveText('now');
  for (let i = 0; i < 6; i++) await expect(page.getByTestId(`temp-${i}`)).toHaveText(/^\d+\.\d °C$/);
  // The time under the cursor, in minutes before now (the axis' ticks use the same words; canvas-drawn),
  // and the readings there.
  const over = chart.locator('.u-over');
  const box = (await over.boundingBox())!;
  await page.mouse.move(box.x + box.width * 0.1, box.y + box.height / 2);
  await expect(at).toHaveText(/^-\d+(\.\d)? (min|s)( \d+ s)?$/);
  for (let i = 0; i < 6; i++) await expect(page.getByTestId(`temp-${i}`)).toHaveText(/^(\d+\.\d °C|—)$/);
  await chart.screenshot({ path: info.outputPath('thermal-chart-cursor.png') });
  await page.screenshot({ path: info.outputPath('thermal-cursor.png'), fullPage: true });
  await page.mouse.move(0, 0);
  await expect(at).toHaveText('now');
  await chart.screenshot({ path: info.outputPath('thermal-chart.png') });
});
