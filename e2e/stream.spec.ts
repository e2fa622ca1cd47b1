// A Mega without an SD card: the app falls back to stream mode (M828) and says it cannot resume.
import { expect, test } from '@playwright/test';
import { openApp } from './transports';

test('streams the test pattern to a Mega without an SD card, each stop once', async ({ page }) => {
  test.setTimeout(90_000);
  const app = await openApp(page, 'web serial', 40, { noSd: true });
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByTestId('start-test').click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
  const printer = app.sim!.printer.module;
  expect(printer.card()).toEqual([]); // nothing spooled: there is no card
  const stops = Number(/stop (\d+) of/.exec((await page.getByTestId('job-state').textContent()) ?? '')?.[1]);
  expect(printer.fires).toBe(stops); // each stop once
  await expect(page.getByTestId('job-state')).toContainText('cannot be resumed');
  app.close();
});
