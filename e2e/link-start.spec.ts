// Issue 29 item 13, a fresh link's first exchange: opening a Mega's USB port resets it, its bootloader
// waits and bytes sent meanwhile are lost, so the app waits for the firmware's `start` before its first
// line, as Marlin hosts do. The simulated printer answers once its worker has loaded the firmware and
// read its card. Over both, a fresh link reports no time-out and no byte sent again.
import { expect, test, type Page } from '@playwright/test';
import { openApp } from './transports';

const NONE_AGAIN = /\b0 resends, 0 time-outs, 0 bytes again\s+\(0\.0 %\)/;

async function linkHealth(page: Page) {
  await page.getByRole('tab', { name: 'LEDs & link' }).click();
  return page.getByText(/^Link: \d+ lines/);
}

test('the simulated printer: a fresh link, and one opened again, with no time-out', async ({ page }, info) => {
  await page.goto('/'); // a fresh page: the worker compiles the firmware and reads its card before it answers
  await expect(page.getByText('Connected to the simulated printer.')).toBeVisible({ timeout: 20_000 });
  const health = await linkHealth(page);
  await expect(health).toHaveText(NONE_AGAIN);
  await page.getByRole('tabpanel').screenshot({ path: info.outputPath('sim-fresh-link.png') });

  // Opened again: the simulated Mega restarts, as at a host's DTR, and says `start` again.
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await expect(page.getByText('Not connected.', { exact: true })).toBeVisible();
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByText('Connected to the simulated printer.')).toBeVisible({ timeout: 20_000 });
  await expect(health).toHaveText(NONE_AGAIN);
  await page.getByRole('tabpanel').screenshot({ path: info.outputPath('sim-link-again.png') });
});

test("Web Serial: the app waits out the Mega's bootloader for `start`, and loses nothing to it", async ({ page }, info) => {
  const opened = await openApp(page, 'web serial');
  await expect(page.getByText('Connected over USB.')).toBeVisible({ timeout: 20_000 });
  const health = await linkHealth(page);
  await expect(health).toHaveText(NONE_AGAIN);
  expect(opened.sim!.lost).toBe(0); // nothing was sent while the bootloader had the port
  // The first line went after the Mega's `start`, numbered from 0.
  const written = opened.fake!.written();
  expect(written).toMatch(/^N0 M110 N0\*\d+#[0-9a-f]{4}\nN1 M115\*/);
  await page.getByRole('tabpanel').screenshot({ path: info.outputPath('serial-fresh-link.png') });
  opened.close();
});
