// Installable and offline: the manifest and icon are served, the service worker takes the app's
// files, and with the network gone a reload still starts the app and its simulated printer.
import { expect, test } from '@playwright/test';

test('installs from its manifest and starts offline from its service worker', async ({ page, context }, info) => {
  await page.goto('/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const manifest = await page.evaluate(async () => {
    const href = document.querySelector('link[rel="manifest"]')!.getAttribute('href')!;
    const m = await (await fetch(href)).json();
    const icon = await fetch(new URL(m.icons[0].src, new URL(href, location.href)));
    return { name: m.name, display: m.display, start: m.start_url, icon: icon.ok && icon.headers.get('content-type') };
  });
  expect(manifest).toEqual({ name: 'UV Exposure', display: 'standalone', start: './', icon: 'image/svg+xml' });
  // `ready` gives the registration once it has an active worker, which may still be activating.
  await expect.poll(() => page.evaluate(async () => (await navigator.serviceWorker.ready).active?.state)).toBe('activated');
  // Everything the page loads is in the worker's list (relative to its scope), the stylesheet included.
  const missing = await page.evaluate(async () => {
    const sw = await (await fetch('/sw.js')).text();
    const loaded = performance.getEntriesByType('resource').map((r) => new URL(r.name).pathname).filter((p) => p.startsWith('/assets/'));
    return loaded.filter((p) => !sw.includes(p.slice(1)));
  });
  expect(missing).toEqual([]);
  // Espressif's flasher is not: it loads only to flash an ESP, which needs the network for its images.
  expect(await page.evaluate(async () => /assets\/(esptool|esp-flash)-/.test(await (await fetch('/sw.js')).text()))).toBe(false);
  await page.reload(); // now under the worker's control, which has cached every file of the build
  await expect.poll(() => page.evaluate(() => !!navigator.serviceWorker.controller)).toBe(true);

  await context.setOffline(true);
  try {
    await page.goto('/?simSpeed=20');
    await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
    await expect(page.getByTestId('firmware')).toHaveText(/UVExposure/);
    await expect(page.getByTestId('thermal-chart').locator('canvas')).toHaveCount(1); // the chart's chunk, from the cache
    await page.getByTestId('start-test').click();
    await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
    await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
    await page.screenshot({ path: info.outputPath('offline.png'), fullPage: true });
  } finally {
    await context.setOffline(false);
  }
});
