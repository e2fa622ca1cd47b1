// Fault injection through the Web Serial transport, where the test holds the simulated printer.
import { expect, test } from '@playwright/test';
import { encodeJob } from '../app/src/protocol/job-encode';
import { testPattern } from '../app/src/device/test-pattern';
import { openApp } from './transports';

test('a job arrives bit-exact through 1 % byte corruption with drops', async ({ page }, info) => {
  test.setTimeout(120_000);
  // The printer runs at 4x: this is about the link, and faster reports would only crowd the page.
  const app = await openApp(page, 'web serial', 4, { link: { corruptPercent: 1, dropPercent: 0.3, seed: 4242 } });
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected', { timeout: 60_000 });
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByTestId('start-test').click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 90_000 });
  const stored = app.sim!.printer.module.card().map(([, text]) => text);
  // The Job panel's full dose, 4 ms, in job format 2: this firmware's M115 says Cap:JOB_FORMAT:2.
  expect(stored).toContain(encodeJob(testPattern(4000), 2));
  await page.getByTestId('tab-link').click();
  await expect(page.getByTestId('link-health')).toContainText(/[1-9]\d* resends|[1-9]\d* time-outs/);
  await page.screenshot({ path: info.outputPath('corrupted-link.png'), fullPage: true });
  app.close();
});

test('a disconnect mid-job leaves the UI truthful', async ({ page }, info) => {
  const app = await openApp(page, 'web serial', 2);
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByTestId('start-test').click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'running', { timeout: 30_000 });
  await app.fake!.lose();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'lost');
  await expect(page.getByTestId('connection')).toContainText('Connection lost');
  await expect(page.getByTestId('lost-job')).toContainText(/The job was running at stop \d+ of \d+/);
  await expect(page.getByTestId('lost-job')).toContainText('the printer may still be exposing');
  await page.screenshot({ path: info.outputPath('lost.png'), fullPage: true });
  app.close();
});

test('over-temperature stops the LEDs and the UI says why', async ({ page }, info) => {
  // LEDs that heat their sensors 1000 °C/s while lit: the head trips its 60 °C limit mid-job.
  const app = await openApp(page, 'web serial', 5, { thermal: { heatingCPerS: 1000 } });
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByTestId('start-test').click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
  await expect(page.getByTestId('faults')).toContainText(/E31 over-temperature/, { timeout: 60_000 });
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'paused');
  await expect(page.getByTestId('job-state')).toContainText('(overtemp)');
  expect(app.sim!.printer.module.lit).toBe(0);
  await page.screenshot({ path: info.outputPath('overtemp.png'), fullPage: true });
  app.close();
});
