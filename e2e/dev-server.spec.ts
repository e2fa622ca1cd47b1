// `npm start` on a fresh clone: the dev server's first page stays put while the app's workers start
// (Vite once reloaded it when it met the work worker's Gerber packages, and a fresh drawing was lost).
import { expect, test } from '@playwright/test';
import { spawn, type ChildProcess } from 'node:child_process';
import { drawFilledRectangle } from './draw';

let server: ChildProcess | undefined;
let origin = '';

test.beforeAll(async () => {
  // --force: the dependency scan runs from nothing, as on a fresh clone. Port 0 is not Vite's: pick one free.
  const port = 5300 + (process.pid % 500);
  server = spawn('npx', ['vite', '--config', 'app/vite.config.ts', '--host', '127.0.0.1', '--port', String(port), '--strictPort', '--force'], {
    stdio: 'ignore',
    detached: true,
  });
  origin = `http://127.0.0.1:${port}`;
  let stopped = '';
  server.on('exit', (code, signal) => (stopped = `the dev server stopped (${code ?? signal})`));
  await expect
    .poll(async () => {
      if (stopped) throw new Error(stopped);
      return fetch(origin + '/').then((r) => r.status, () => 0);
    }, { timeout: 60_000 })
    .toBe(200);
});

test.afterAll(() => {
  if (server?.pid) process.kill(-server.pid, 'SIGTERM');
});

test('a fresh dev server never reloads the page: a drawing made at once survives its workers starting', async ({ page }, info) => {
  test.setTimeout(90_000);
  let loads = 0;
  page.on('load', () => loads++);
  await page.goto(origin + '/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected', { timeout: 30_000 });
  await drawFilledRectangle(page, [0.3, 0.3], [0.5, 0.5]);
  // The preview starts the work worker, whose imports the dependency scan must already have met.
  await page.getByTestId('view-preview').click();
  await expect(page.getByTestId('preview-summary')).toBeVisible({ timeout: 30_000 });
  await page.waitForTimeout(3000); // Vite's reload, when it came, came within a second of the worker's start
  expect(loads).toBe(1);
  await page.getByTestId('view-draw').click();
  await expect(page.getByTestId('undo')).toBeEnabled(); // the drawing is still the page's
  await page.screenshot({ path: info.outputPath('after-workers.png'), fullPage: true });
});
