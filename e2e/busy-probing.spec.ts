// Issue 41 item 2: probing the bed, writing settings and flashing are in the one rule (job/actions.ts).
// While the probe maps the bed every control is closed and says so, a second probing cannot interleave
// (it once ended in E41), and neither Apply nor Flash is open under a running job.
import { expect, test, type Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';
import { allClosed, expectControls } from './machine-controls';

async function open(page: Page, speed: number) {
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto(`/?simSpeed=${speed}`);
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
}

const flashButton = (page: Page) => page.getByTestId('panel-firmware').getByRole('button', { name: 'Flash', exact: true });

test('probing the bed closes every control, says "Probing…", and ends without a second probing in between', async ({ page }, info) => {
  test.setTimeout(180_000);
  await open(page, 1); // a 3 × 3 mesh takes some 25 s at real time
  await drawFilledRectangle(page, [0.3, 0.3], [0.32, 0.32]);
  await page.getByRole('tab', { name: 'Firmware' }).click();
  await expect(page.getByTestId('firmware-view')).toBeVisible();
  await expect(page.getByTestId('firmware-flash-closed')).toHaveCount(0); // an idle machine may be flashed

  await page.getByRole('tab', { name: 'Probe & mesh' }).click();
  await page.getByRole('tabpanel').getByRole('button', { name: 'Probe the bed', exact: true }).click();
  await page.getByRole('dialog').getByRole('button', { name: 'Home and continue' }).click(); // a fresh machine homes first
  await expect(page.getByTestId('probing-state')).toHaveText(/^Probing…/, { timeout: 30_000 });
  const atWork = /the probe is at work/;
  await expectControls(page, info, 'probing', allClosed(atWork, { Pause: /no job is running/, Continue: /no job is paused/, Stop: /no job is running/ }));
  await page.getByRole('tab', { name: 'Firmware' }).click();
  await expect(flashButton(page)).toBeDisabled();
  await expect(flashButton(page)).toHaveAttribute('title', /the probe is at work.*: flashing restarts the board/);
  await expect(page.getByTestId('firmware-flash-closed')).toBeVisible();
  await page.screenshot({ path: info.outputPath('probing-firmware.png'), fullPage: true });

  // The mesh comes, every control opens again, and no probe error was raised.
  await page.getByRole('tab', { name: 'Probe & mesh' }).click();
  await expect(page.getByTestId('mesh-stats')).toBeVisible({ timeout: 90_000 });
  await expect(page.getByRole('tabpanel').getByRole('button', { name: 'Probe the bed', exact: true })).toBeEnabled({ timeout: 10_000 });
  await expect(page.getByTestId('probing-state')).toHaveCount(0);
  await expect(page.getByRole('button', { name: 'Expose test pattern' })).toBeEnabled();
  await expect(page.getByTestId('faults')).toHaveCount(0);
});

test('a running job closes Apply and Flash, each with its reason', async ({ page }, info) => {
  test.setTimeout(120_000);
  await open(page, 1);
  await drawFilledRectangle(page, [0.3, 0.3], [0.32, 0.32]);
  await page.getByRole('tab', { name: 'Settings' }).click();
  await page.getByTestId('setting-speed.travel').fill('120');
  await expect(page.getByTestId('settings-apply')).toBeEnabled(); // idle: the change may be set
  await page.getByTestId('setting-speed.travel').fill('100');

  await page.getByLabel('Full dose').fill('100');
  await page.getByTestId('strategy').selectOption('serpentine');
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of/, { timeout: 30_000 });

  await page.getByRole('tab', { name: 'Settings' }).click();
  await page.getByTestId('setting-speed.travel').fill('120'); // the tester's case: X travel sent mid-job
  await expect(page.getByTestId('settings-apply')).toBeDisabled();
  await expect(page.getByTestId('settings-apply')).toHaveAttribute('title', 'Not now: a job is running');
  await page.screenshot({ path: info.outputPath('running-settings.png'), fullPage: true });
  await page.getByRole('tab', { name: 'Firmware' }).click();
  await expect(flashButton(page)).toBeDisabled();
  await expect(page.getByTestId('firmware-flash-closed')).toHaveText('Not now: a job is running: flashing restarts the board.');
  await page.screenshot({ path: info.outputPath('running-firmware.png'), fullPage: true });
  await page.getByRole('button', { name: 'Stop', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'aborted');
  await page.getByRole('tab', { name: 'Settings' }).click();
  await page.getByTestId('setting-speed.travel').fill('120');
  await expect(page.getByTestId('settings-apply')).toBeEnabled(); // the job is over: it may be set now
});
