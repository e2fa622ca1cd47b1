// Issue 17, item 7: the console shows the replies to what the user typed without ticking
// "reports"; the auto-reports (a temperature line every second) stay filtered.
import { expect, test } from '@playwright/test';

test('M105, M114 and M503 answer in the console; auto-reports stay hidden', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const consoleRegion = page.getByRole('region', { name: 'Console' });
  const input = consoleRegion.getByRole('textbox', { name: 'A line for the printer' });
  const log = consoleRegion.getByRole('list');
  await expect(consoleRegion.getByLabel('reports')).not.toBeChecked();

  await input.fill('M105');
  await input.press('Enter');
  await expect(log.getByText(/^\S+ T:\d+\.\d \/\d+\.\d S0:/)).toHaveCount(1); // its reply, and no auto-report
  await input.fill('M114');
  await input.press('Enter');
  await expect(log.getByText(/X:\d+\.\d{3} Y:\d+\.\d{3} Z:/)).toHaveCount(1);
  await input.fill('M503');
  await input.press('Enter');
  await expect(log.getByText('M850 pitch.x 50').last()).toBeVisible();
  // Two seconds at 20× are 40 temperature auto-reports: none of them shows.
  await page.waitForTimeout(2000);
  await expect(log.getByText(/^\S+ T:\d+\.\d \/\d+\.\d S0:/)).toHaveCount(1);
  await consoleRegion.screenshot({ path: info.outputPath('console-replies.png') });
  // Ticked, the reports come in too.
  await consoleRegion.getByLabel('reports').check();
  await expect.poll(() => log.getByText(/T:\d+\.\d \/\d+\.\d S0:/).count()).toBeGreaterThan(3);
});
