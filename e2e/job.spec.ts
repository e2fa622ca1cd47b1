// Job control on the simulated printer: framing with the LEDs off, and resuming a job that a
// restart interrupted (reopening the link restarts the machine, as a real Mega's USB port does).
import { expect, test } from '@playwright/test';

test('a job interrupted by a restart is offered for resume on connect, and runs to its end', async ({ page }, info) => {
  await page.goto('/?simSpeed=4');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
  await page.getByTestId('start-test').click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop ([1-9]\d*) of/, { timeout: 30_000 });
  await expect(page.getByTestId('eta')).toContainText(/left, done at about/);
  await page.screenshot({ path: info.outputPath('running.png'), fullPage: true });

  // Unplug and plug in again: the Mega restarts, and its card holds the checkpoint.
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const offer = page.getByTestId('resume-offer');
  await expect(offer).toContainText(/test-pattern-1\.uvj.*: [1-9]\d* of \d+ stops are done/);
  await page.screenshot({ path: info.outputPath('offer.png'), fullPage: true });
  await page.getByTestId('resume-job').click();
  await expect(offer).toHaveCount(0);
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'running', { timeout: 30_000 });
  await expect(page.getByTestId('console-log')).toContainText('echo:resume: stop');
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
  await expect(page.getByTestId('job-state')).toContainText(/done: stop (\d+) of \1/);

  // Nothing is left to resume.
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
});

test('a discarded interrupted job is not offered again', async ({ page }) => {
  await page.goto('/?simSpeed=4');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('start-test').click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]/, { timeout: 30_000 });
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await page.getByTestId('discard-job').click();
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
});
