// Every user flow through each transport: Web Serial, the ESP, and the built-in simulated printer.
import { expect, test } from '@playwright/test';
import { openApp, TRANSPORTS } from './transports';

for (const transport of TRANSPORTS) {
  test.describe(`over ${transport}`, () => {
    test('connects, shows the firmware and six temperatures', async ({ page }, info) => {
      const app = await openApp(page, transport);
      await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
      await expect(page.getByTestId('firmware')).toHaveText(/^UVExposure 0\.1\.0/);
      for (let i = 0; i < 6; i++) await expect(page.getByTestId(`temp-${i}`)).toHaveText(/^-?\d+\.\d °C$/);
      await page.screenshot({ path: info.outputPath('connected.png'), fullPage: true });
      app.close();
    });

    test('uploads and exposes the test pattern to the end', async ({ page }, info) => {
      const app = await openApp(page, transport);
      await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
      await page.getByTestId('start-test').click();
      await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
      // At 40x the job may already be done when we look.
      await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
      await page.screenshot({ path: info.outputPath('running.png'), fullPage: true });
      await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
      // The automatic order: the pattern's few lit cells may run as passes on the move, or as stops.
      await expect(page.getByTestId('job-state')).toContainText(/done: (stop|pass) (\d+) of \2/);
      const [, unit, count] = /(stop|pass) (\d+) of/.exec((await page.getByTestId('job-state').textContent()) ?? '') ?? [];
      if (app.sim && unit === 'stop') expect(app.sim.printer.module.fires).toBe(Number(count)); // each stop fired once
      await page.screenshot({ path: info.outputPath('done.png'), fullPage: true });
      app.close();
    });

    test('pauses, continues and stops a job', async ({ page }) => {
      // At 1× the test pattern runs for long enough that a loaded machine still sees it running
      // before it ends (at 4× it could end first).
      const app = await openApp(page, transport, 1);
      await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
      await page.getByTestId('start-test').click();
      await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
      await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'running', { timeout: 30_000 });
      await page.getByRole('button', { name: 'Pause' }).click();
      await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'paused');
      await page.getByRole('button', { name: 'Continue' }).click();
      await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'running');
      await page.getByTestId('stop-job').click();
      await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'aborted');
      if (app.sim) expect(app.sim.printer.module.lit).toBe(0);
      app.close();
    });
  });
}
