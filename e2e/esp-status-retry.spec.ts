// The app as the hub serves it (its flash image from the ESP's own core built for the host: gzip, plain
// http) when GET /status is refused with 503 `overloaded`, which protocol/esp.md allows: the page asks
// again after a back-off and connects; it never falls back on a simulated printer its image has not got.
import { expect, test } from '@playwright/test';
import { startEspHost, type EspHost } from './esp-host';

let host: EspHost;
test.beforeEach(async () => {
  host = await startEspHost(20);
});
test.afterEach(() => host.stop());

const OVERLOADED = { status: 503, contentType: 'application/json', body: JSON.stringify({ error: { code: 'overloaded', message: 'too many requests are waiting; try again' } }) };

test('a 503 overloaded on GET /status once: the page connects on a retry', async ({ page }) => {
  const asked: number[] = [];
  await page.route('**/status', async (route) => {
    asked.push(Date.now());
    if (asked.length === 1) return route.fulfill(OVERLOADED);
    return route.continue();
  });
  await page.goto(host.url);
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('firmware')).toHaveText(/UVExposure/);
  expect(asked.length).toBe(2);
  expect(asked[1] - asked[0]).toBeGreaterThanOrEqual(200); // after the back-off, not at once
  await expect(page.getByTestId('device-kind')).toHaveValue('esp');
  await expect(page.getByTestId('device-kind').locator('option[value="esp"]')).toBeEnabled();
  await expect(page.getByText('no simulated printer')).toHaveCount(0);
});

test('a hub that never answers GET /status leaves Wi-Fi chosen and selectable, never "no simulated printer"', async ({ page }) => {
  let asked = 0;
  await page.route('**/status', (route) => (asked++, route.fulfill(OVERLOADED)));
  await page.goto(host.url);
  // The back-off ends (3.75 s), and the page goes on to the hub's WebSocket, which does answer.
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected', { timeout: 15_000 });
  expect(asked).toBe(5);
  await expect(page.getByTestId('device-kind')).toHaveValue('esp');
  await expect(page.getByTestId('device-kind').locator('option[value="esp"]')).toBeEnabled();
  await expect(page.getByText('no simulated printer')).toHaveCount(0);
});
