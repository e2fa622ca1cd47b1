// The app as GitHub Pages publishes it (npm run build:pages, served under /uv-printer/ by a server with
// Pages' headers: e2e/pages-server.ts): offline after one visit, a redeploy picked up without a blank
// page, and a page left open across a deploy that still opens what it had not loaded.
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import type { Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';
import { expect, test } from './pages-builds';
import { startPagesServer, type PagesServer } from './pages-server';

let server: PagesServer;
test.beforeEach(async ({ builds }) => {
  server = await startPagesServer(builds.a.dir);
});
test.afterEach(() => server.close());

/** The app is on screen and talks to its simulated printer: never a blank page. */
async function running(page: Page, version: string): Promise<void> {
  await expect(page.getByRole('heading', { name: /UV Exposure/ })).toBeVisible();
  await expect(page.getByTestId('app-version')).toHaveText(version);
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
}

/** The worker runs this page, with every file of its version cached (activate comes after install). */
async function controlled(page: Page): Promise<void> {
  await expect.poll(() => page.evaluate(() => navigator.serviceWorker.controller?.state ?? null)).toBe('activated');
}

const panelsChunk = (dir: string) => readdirSync(join(dir, 'assets')).find((f) => /^panels-.*\.js$/.test(f))!;

test('one visit, then offline with the HTTP cache cleared: the app reaches its simulated printer and opens every view', async ({ page, context, builds }, info) => {
  await page.goto(server.url);
  await running(page, builds.a.version);
  // The worker sits beside the page, its scope the app's folder, not the whole OWNER.github.io.
  expect(await page.evaluate(async () => (await navigator.serviceWorker.ready).scope)).toBe(server.url);
  await controlled(page);

  const cdp = await context.newCDPSession(page);
  await cdp.send('Network.clearBrowserCache');
  await context.setOffline(true);
  const seen = server.requests.length;
  try {
    await page.reload();
    await running(page, builds.a.version);
    await expect(page.getByTestId('firmware')).toHaveText(/UVExposure/);
    const tabs = page.getByRole('tablist', { name: 'Dashboards' }).getByRole('tab');
    const ids = await tabs.evaluateAll((t) => t.map((e) => e.getAttribute('data-testid')!.replace(/^tab-/, '')));
    expect(ids).toEqual(['thermal', 'position', 'probe', 'link', 'settings', 'firmware', 'simulator']);
    for (const id of ids) {
      await page.getByTestId(`tab-${id}`).click();
      const panel = page.getByTestId(`panel-${id}`);
      await expect(panel.getByTestId('lazy-loading')).toHaveCount(0);
      await expect(panel.getByTestId('lazy-failed')).toHaveCount(0);
      await expect(panel.locator('input, button, select, canvas, table').first()).toBeVisible();
    }
    // The work's own views: the exposure preview (once something is drawn) and the material test.
    await drawFilledRectangle(page, [0.2, 0.2], [0.4, 0.4]);
    await page.getByTestId('view-preview').click();
    await expect(page.getByRole('button', { name: 'Plan again' })).toBeVisible();
    await page.getByRole('button', { name: 'Material test…' }).click();
    await expect(page.getByRole('button', { name: 'Make the test project' })).toBeVisible();
    await expect(page.getByText(/could not be loaded/)).toHaveCount(0);
    await page.screenshot({ path: info.outputPath('offline.png'), fullPage: true });
    expect(server.requests.length).toBe(seen); // nothing reached the server
  } finally {
    await context.setOffline(false);
  }
});

test('a redeploy two minutes after a visit is running after at most two reloads, never a blank page', async ({ page, context, builds }, info) => {
  // Every response left two minutes old: the visit was two minutes ago, and the HTTP cache (max-age 600)
  // still holds that visit's index.html as fresh.
  server.cachedFor = 120;
  await page.goto(server.url);
  await running(page, builds.a.version);
  await controlled(page);
  server.cachedFor = 0;
  server.deploy(builds.b.dir);
  const deployedAt = server.requests.length;

  // The trap is armed: past the worker, the browser's HTTP cache still answers with the old index.html.
  const other = await context.newPage();
  const cdp = await context.newCDPSession(other);
  await cdp.send('Network.setBypassServiceWorker', { bypass: true });
  await other.goto(`${server.url}icon.svg`);
  const cachedIndex = await other.evaluate(async () => (await fetch('index.html')).text());
  expect(cachedIndex).toContain(readdirSync(join(builds.a.dir, 'assets')).find((f) => /^index-.*\.js$/.test(f)));
  await other.close();

  // First reload: the cached old version starts (whole), and hears of the new one.
  await page.reload();
  await running(page, builds.a.version);
  await expect(page.getByTestId('update-ready')).toBeVisible();
  await expect(page.getByTestId('update-ready')).toHaveText(/A new version of the app is ready\./);
  await page.getByTestId('update-ready').screenshot({ path: info.outputPath('update-ready.png') });
  // The new worker took its files from the network, not from the HTTP cache.
  const fetched = server.requests.slice(deployedAt).filter((r) => r.path === '/uv-printer/index.html');
  expect(fetched.length).toBeGreaterThan(0);
  expect(fetched.every((r) => r.status === 200 && r.headers['cache-control'] === 'no-cache')).toBe(true);

  // Second reload: the new version.
  await page.reload();
  await running(page, builds.b.version);
  await expect(page.getByTestId('update-ready')).toHaveCount(0);
  // No page runs the old version any more: its files are dropped.
  await expect.poll(() => page.evaluate(async () => (await caches.keys()).filter((k) => k !== 'uv-exposure-pages').length)).toBe(1);
});

test('a page left open across a deploy still opens a view it had not loaded', async ({ page, builds }, info) => {
  await page.goto(server.url);
  await running(page, builds.a.version);
  await controlled(page);
  const chunk = panelsChunk(builds.a.dir);
  expect(panelsChunk(builds.b.dir)).not.toBe(chunk); // the deploy takes the view's chunk away
  server.deploy(builds.b.dir);
  expect((await page.request.get(`${server.url}assets/${chunk}`)).status()).toBe(404);

  // The open page hears of the deploy (as when it comes back into view), and the new worker takes over.
  await page.evaluate(async () => (await navigator.serviceWorker.getRegistration())!.update());
  await expect(page.getByTestId('update-ready')).toBeVisible();
  await expect.poll(() => page.evaluate(async () => (await navigator.serviceWorker.getRegistration())!.waiting === null)).toBe(true);
  await expect(page.getByTestId('app-version')).toHaveText(builds.a.version); // not reloaded under the person

  // Later than max-age: the browser's HTTP cache no longer holds the old chunk (the worker's install
  // had put it there), and the server answers 404 for it. Only the worker's kept files can serve it.
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Network.clearBrowserCache');
  const asked = server.requests.length;
  await page.getByTestId('tab-settings').click();
  const panel = page.getByTestId('panel-settings');
  await expect(panel.getByTestId('lazy-loading')).toHaveCount(0);
  await expect(panel.getByTestId('lazy-failed')).toHaveCount(0);
  await expect(panel.locator('input, button').first()).toBeVisible();
  expect(server.requests.slice(asked).filter((r) => r.path.endsWith(chunk))).toEqual([]);
  await page.screenshot({ path: info.outputPath('open-across-deploy.png') });
});

test('during a job, a new version waits: the page says so and does not change under the job', async ({ page, builds }, info) => {
  await page.goto(`${server.url}?simSpeed=4`);
  await running(page, builds.a.version);
  await controlled(page);
  await page.getByTestId('full-ms').fill('40');
  await page.getByTestId('strategy').selectOption('serpentine');
  await page.getByTestId('start-test').click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running/, { timeout: 30_000 });

  server.deploy(builds.b.dir);
  await page.evaluate(async () => (await navigator.serviceWorker.getRegistration())!.update());
  await expect(page.getByTestId('update-ready')).toHaveText(/ready: it takes over when you reload, after this job\./);
  await page.getByTestId('update-ready').screenshot({ path: info.outputPath('update-during-job.png') });
  await page.waitForTimeout(1000); // a second more: still waiting, still the same page
  expect(await page.evaluate(async () => (await navigator.serviceWorker.getRegistration())!.waiting?.state)).toBe('installed');
  await expect(page.getByTestId('app-version')).toHaveText(builds.a.version);
  await expect(page.getByTestId('job-state')).toContainText(/running/);
});

test.describe('without a service worker', () => {
  test.use({ serviceWorkers: 'block' });

  test('a view whose chunk a deploy took away says to reload, and the reload brings the new version', async ({ page, builds }) => {
    await page.goto(server.url);
    await running(page, builds.a.version);
    server.deploy(builds.b.dir);
    await page.getByTestId('tab-settings').click();
    const failed = page.getByTestId('panel-settings').getByTestId('lazy-failed');
    await expect(failed).toContainText('the app was updated since this page was opened: reload the page for the current version');
    await expect(failed).not.toContainText('hub');
    await failed.getByRole('button', { name: 'Reload the page' }).click();
    await running(page, builds.b.version);
    await page.getByTestId('tab-settings').click();
    await expect(page.getByTestId('panel-settings').locator('input, button').first()).toBeVisible();
  });
});
