// The views that load on demand (docs/app.md "Size"): a loading line while their chunk comes, and what went
// wrong when it cannot come (the printer's hub went away), never an empty panel.
import { expect, test } from '@playwright/test';
import { startEspHost } from './esp-host';

// The page's own requests only: a service worker would answer them from its cache.
test.use({ serviceWorkers: 'block' });

const PANELS = /\/assets\/panels-[\w-]+\.js$/;

test('a tab says it is loading, then shows its panel', async ({ page }) => {
  let release = () => {};
  const held = new Promise<void>((r) => (release = r));
  await page.route(PANELS, async (route) => {
    await held;
    await route.continue();
  });
  await page.goto('/');
  await page.getByTestId('tab-settings').click();
  await expect(page.getByTestId('panel-settings').getByTestId('lazy-loading')).toHaveText('Loading the settings…');
  release();
  await expect(page.getByTestId('panel-settings').getByTestId('lazy-loading')).toHaveCount(0);
  await expect(page.getByTestId('panel-settings').getByTestId('lazy-failed')).toHaveCount(0);
  await expect(page.getByTestId('panel-settings').locator('input, button').first()).toBeVisible();
});

test('a tab whose chunk cannot load says so, and so does a device whose link cannot', async ({ page }) => {
  await page.route(PANELS, (route) => route.abort());
  await page.route(/\/assets\/chosen-links-[\w-]+\.js$/, (route) => route.abort());
  await page.goto('/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('tab-position').click();
  await expect(page.getByTestId('panel-position').getByRole('alert')).toContainText('The position dashboard could not be loaded');
  // Served by a website (not the printer's hub): the message does not blame the hub.
  await expect(page.getByTestId('panel-position').getByRole('alert')).toContainText('reload the page for the current version');
  await expect(page.getByTestId('panel-position').getByRole('alert')).not.toContainText('hub');
  // The chunk comes back (the network did): trying again shows the panel, with no reload.
  await page.unroute(PANELS);
  await page.getByTestId('panel-position').getByTestId('lazy-retry').click();
  await expect(page.getByTestId('panel-position').getByRole('alert')).toHaveCount(0);
  await expect(page.getByTestId('panel-position').locator('input, button').first()).toBeVisible();
  await page.route(PANELS, (route) => route.abort());

  // USB's transport loads when it is chosen: without it, the connection says why.
  await page.addInitScript(() => Object.defineProperty(navigator, 'serial', { value: { requestPort: () => Promise.reject(new Error('unused')) } }));
  await page.reload();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('device-kind').selectOption('serial');
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'error');
  await expect(page.getByTestId('connection')).toContainText('its code could not be loaded');
});

test('served by the printer\'s hub, a tab whose chunk cannot load names the hub, and loads when it is back', async ({ page }) => {
  const hub = await startEspHost(20); // the hub's own C++, serving the ESP's image (npm run build:esp)
  try {
    await page.route(PANELS, (route) => route.abort());
    await page.goto(hub.url);
    await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
    await page.getByTestId('tab-settings').click();
    await expect(page.getByTestId('panel-settings').getByRole('alert')).toContainText("Try again once the printer's hub can be reached");
    await page.unroute(PANELS);
    await page.getByTestId('panel-settings').getByTestId('lazy-retry').click();
    await expect(page.getByTestId('panel-settings').locator('input, button').first()).toBeVisible();
  } finally {
    hub.stop();
  }
});
