// Issue 17, item 11: the simulated printer's panel. Its speed, and the faults it models (corrupted and
// dropped bytes, stalls, a pulled cable, over-temperature, a probe alarm, a missing printhead), each
// set from a labelled control while it runs, and seen where a person sees their effects.
import { expect, test, type Page } from '@playwright/test';

async function openPanel(page: Page, speed: number) {
  await page.goto(`/?simSpeed=${speed}`);
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await expect(page.getByLabel('Speed (× real time)')).toBeVisible();
}

async function typeLine(page: Page, line: string) {
  const input = page.getByRole('textbox', { name: 'A line for the printer' });
  await input.fill(line);
  await input.press('Enter');
}

test('the panel is there only for the simulated printer, and labels every control', async ({ page }, info) => {
  await openPanel(page, 20);
  for (const label of ['Speed (× real time)', 'Corrupted bytes (%)', 'Dropped bytes (%)', 'Stall length (ms)', 'Stall every (ms)', 'Extra heating (°C/s)']) {
    await expect(page.getByRole('spinbutton', { name: label })).toBeVisible();
  }
  await expect(page.getByRole('spinbutton', { name: 'Speed (× real time)' })).toHaveValue('20');
  await expect(page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' })).not.toBeChecked();
  for (const name of ['Pull the USB cable', 'Probe alarm on next deploy', 'Clear faults']) await expect(page.getByRole('button', { name })).toBeVisible();
  await expect(page.getByTestId('simulator-kept')).toContainText('Kept in this browser');
  await page.screenshot({ path: info.outputPath('panel.png'), fullPage: true });
  // Another device chosen: the panel goes.
  await page.getByTestId('device-kind').selectOption('serial');
  await expect(page.getByRole('tab', { name: 'Simulated printer' })).toHaveCount(0);
  await expect(page.getByRole('tab', { name: 'Thermal', selected: true })).toBeVisible();
});

test('the speed changes while a job runs, and the address keeps it for a reload', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openPanel(page, 1);
  await page.getByLabel('Full dose').fill('100'); // about 20 s of exposing at real time
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of/, { timeout: 60_000 });
  await page.screenshot({ path: info.outputPath('real-time.png'), fullPage: true });
  // At 200x what is left takes a tenth of a second.
  await page.getByLabel('Speed (× real time)').fill('200');
  await expect(page).toHaveURL(/simSpeed=200/);
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 8_000 });
  await page.screenshot({ path: info.outputPath('fast.png'), fullPage: true });
  await page.reload();
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await expect(page.getByLabel('Speed (× real time)')).toHaveValue('200');
});

test('a missing printhead and an overheating one are reported as faults', async ({ page }, info) => {
  test.setTimeout(90_000); // three waits on the printer's own time, each up to 30 s on a loaded machine
  await openPanel(page, 2);
  await page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' }).check();
  await expect(page.getByTestId('faults')).toContainText('E30 printhead not responding', { timeout: 10_000 });
  await page.screenshot({ path: info.outputPath('missing-nano.png'), fullPage: true });

  // About 20 s of exposing at real time (10 s at 2x): the job still runs when the head overheats.
  await page.getByLabel('Full dose').fill('100');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  // The dialog asks the printhead first (M105): it is silent, so the job is refused.
  const dialog = page.getByRole('dialog');
  await expect(page.getByTestId('dry-run')).toContainText('machine: E30 printhead not responding', { timeout: 15_000 });
  await expect(dialog).toContainText('Not exposed: fix what is marked above.');
  // The printhead is back while the question is open (the modal keeps the panel from the pointer, so
  // the click is sent to the checkbox itself): the app asks it again, and the verdict follows.
  await page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' }).dispatchEvent('click');
  await expect(page.getByTestId('dry-run')).toContainText('machine: the printhead answers, and the machine reports no fault', { timeout: 15_000 });
  await dialog.getByRole('button', { name: 'Expose now' }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of/, { timeout: 30_000 });
  await page.getByLabel('Extra heating (°C/s)').fill('20'); // past the 55 °C limit in under 2 s of the printer's time
  await expect(page.getByTestId('faults')).toContainText(/E31 over-temperature/, { timeout: 30_000 });
  await expect(page.getByTestId('job-state')).toContainText('paused (overtemp)');
  await page.getByRole('tab', { name: 'LEDs & link' }).click();
  await expect(page.getByTestId('led-state')).toHaveAttribute('data-lit', 'false');
  await page.screenshot({ path: info.outputPath('overtemp.png'), fullPage: true });
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByRole('button', { name: 'Clear faults' }).click();
  await expect(page.getByLabel('Extra heating (°C/s)')).toHaveValue('0');
});

test('the probe alarms on its next deploy, once', async ({ page }, info) => {
  await openPanel(page, 20);
  await page.getByRole('button', { name: 'Probe alarm on next deploy' }).click();
  await expect(page.getByTestId('panel-simulator')).toContainText('armed');
  await page.getByRole('tab', { name: 'Probe & mesh' }).click();
  await page.getByRole('button', { name: 'Deploy' }).click();
  await expect(page.getByTestId('probe-state')).toHaveText('alarm');
  await page.screenshot({ path: info.outputPath('probe-alarm.png'), fullPage: true });
  await page.getByRole('button', { name: 'Reset alarm' }).click();
  await page.getByRole('button', { name: 'Deploy' }).click();
  await expect(page.getByTestId('probe-state')).toHaveText('deployed');
});

test('corrupted and dropped bytes and stalls show in the link health', async ({ page }, info) => {
  await openPanel(page, 1);
  await page.getByLabel('Corrupted bytes (%)').fill('3');
  await page.getByLabel('Dropped bytes (%)').fill('1');
  await page.getByLabel('Stall length (ms)').fill('600');
  await page.getByLabel('Stall every (ms)').fill('1000');
  for (let i = 0; i < 6; i++) await typeLine(page, 'M114');
  await page.getByRole('tab', { name: 'LEDs & link' }).click();
  await expect(page.getByTestId('link-health')).toContainText(/[1-9]\d* resends|[1-9]\d* time-outs/, { timeout: 30_000 });
  await page.screenshot({ path: info.outputPath('noisy-link.png'), fullPage: true });
});

test('pulling the USB cable mid-job loses the link; the printer runs on, and connecting again offers the job', async ({ page }, info) => {
  await openPanel(page, 2);
  await page.getByLabel('Full dose').fill('40');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of/, { timeout: 30_000 });
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByRole('button', { name: 'Pull the USB cable' }).click();
  await expect(page.getByTestId('connection')).toContainText("Connection lost: the simulated printer's USB cable was pulled.");
  await expect(page.getByTestId('lost-job')).toContainText(/The job was running at stop \d+ of \d+ when the link dropped;\s+the printer may still be exposing/);
  await page.screenshot({ path: info.outputPath('cable-pulled.png'), fullPage: true });
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await expect(page.getByTestId('resume-offer')).toContainText(/test-pattern-1\.uvj: \d+ of \d+ stops are done/);
});

test("the panel shows the Mega's display as its firmware draws it, and a message sent to it", async ({ page }, info) => {
  await openPanel(page, 20);
  const oled = page.getByTestId('oled');
  await expect(oled).toContainText('UV ready'); // the firmware's own status line (firmware/mega/src/screen.cpp)
  await typeLine(page, 'M117 HELLO BOARD');
  await expect(oled).toContainText('HELLO BOARD');
  await typeLine(page, 'G28');
  await expect(oled).toContainText(/X\s*0\.0/, { timeout: 30_000 });
  await page.locator('figure.oled').screenshot({ path: info.outputPath('oled.png') });
});
