// The console: raw lines to the simulated printer, its answers in the log by level, the filter and the debug view.
import { expect, test } from '@playwright/test';

test('sends raw lines, shows the answers by level, and filters the log', async ({ page }, info) => {
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const input = page.getByTestId('console-input');
  const log = page.getByTestId('console-log');
  await input.fill('M115');
  await input.press('Enter');
  await expect(log.locator('li[data-level="sent"]', { hasText: 'M115' })).toBeVisible();
  await expect(log.locator('li[data-level="info"]', { hasText: 'FIRMWARE_NAME:UVExposure' }).last()).toBeVisible();
  await input.fill('M9999');
  await input.press('Enter');
  await expect(log.locator('li[data-level="error"]', { hasText: 'echo:E10 unknown command' })).toBeVisible();
  await expect(page.getByTestId('console-error')).toContainText('unknown command');
  // Reports (every second) and the link's oks are hidden until asked for.
  await expect(log.locator('li[data-level="report"]')).toHaveCount(0);
  await expect(log.locator('li[data-level="link"]')).toHaveCount(0);
  await page.getByTestId('console-debug').check();
  await expect(log.locator('li[data-level="link"]').first()).toBeVisible();
  await page.getByTestId('console-filter').fill('firmware_name');
  await expect(log.locator('li')).toHaveCount(2); // the app's own M115 on connecting, and ours
  // The up arrow brings back the last line sent.
  await input.press('ArrowUp');
  await expect(input).toHaveValue('M9999');
  await page.screenshot({ path: info.outputPath('console.png'), fullPage: true });
});
