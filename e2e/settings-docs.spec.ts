// Issue 17, item 10: each setting shows its name in words, unit, range and a one-line description
// (from firmware/mega/CONFIG.md), and a value that is not a number says so.
import { expect, test } from '@playwright/test';

test('settings read as words with units and ranges; "abc" is not a number, 0 is out of range', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByRole('tab', { name: 'Settings' }).click();
  const pitch = page.getByLabel('X cell pitch');
  await expect(pitch).toHaveValue('50');
  await expect(pitch).toHaveAccessibleDescription(/default cell pitch along X for jobs made on the printer; 1 to 100000 whole\. pitch\.x/);
  const row = page.locator('.setting', { has: pitch });
  await expect(row).toContainText('µm');
  await expect(page.getByLabel('Soft limit, LED 3 sensor')).toHaveAccessibleDescription(/soft limit for sensor A3/);
  await pitch.fill('abc');
  await expect(page.getByTestId('settings-invalid')).toHaveText('Not sent: X cell pitch: not a number.');
  await expect(pitch).toHaveAccessibleDescription(/^not a number\./);
  await expect(page.getByRole('button', { name: 'Apply', exact: true })).toBeDisabled();
  await row.screenshot({ path: info.outputPath('pitch-not-a-number.png') });
  await pitch.fill('0');
  await expect(page.getByTestId('settings-invalid')).toHaveText('Not sent: X cell pitch: out of range: 1 to 100000.');
  await page.getByTestId('panel-settings').screenshot({ path: info.outputPath('settings.png') });
});
