// Issue 29, items 1 and 3-5: a machine with a fault or a hot head. The dry run shows the machine's
// faults; the over-temperature screen keeps Continue closed while the head is hot and says so in good
// grammar, and its fault goes once the job goes on; a paced job (and its cooling, walked over every
// control) is told in its paced times. Soft limits set below the room's temperature (M850) hold a
// head "hot" for as long as a test needs.
import { expect, test, type Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';
import { allClosed, expectControls } from './machine-controls';

async function open(page: Page, speed: number) {
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto(`/?simSpeed=${speed}`);
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
}

async function typeLine(page: Page, line: string) {
  const input = page.getByRole('textbox', { name: 'A line for the printer' });
  await input.fill(line);
  await input.press('Enter');
  await expect(page.getByTestId('console-log')).toContainText(line);
}

/** Sets the soft limits (°C) and reads the settings again, as the app then judges by them. */
async function setLimits(page: Page, limits: Record<number, number>) {
  for (const [i, c] of Object.entries(limits)) await typeLine(page, `M850 thermal.limit.${i} ${c}`);
  await page.getByRole('tab', { name: 'Settings' }).click();
  await page.getByRole('button', { name: 'Read again' }).click();
  await page.getByRole('tab', { name: 'Thermal' }).click();
}

async function startTestPattern(page: Page, doseMs: string) {
  await page.getByLabel('Full dose').fill(doseMs);
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of/, { timeout: 30_000 });
}

const job = (page: Page) => page.getByRole('region', { name: 'Job' });

test('item 3: the dry run shows a silent printhead as a red line, and offers no exposure', async ({ page }, info) => {
  await open(page, 20);
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  const missing = page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' });
  await missing.check();
  await expect(page.getByTestId('faults')).toContainText('E30 printhead not responding', { timeout: 15_000 });

  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the test pattern?' });
  await expect(dialog.locator('li[data-level="error"]')).toHaveText('machine: E30 printhead not responding. The printer would refuse the job: clear the fault first');
  await expect(dialog).toContainText('Not exposed: fix what is marked above.');
  await expect(dialog.getByRole('button', { name: /Expose/ })).toHaveCount(0);
  await dialog.screenshot({ path: info.outputPath('dry-run-printhead-missing.png') });
  await dialog.getByRole('button', { name: 'Close' }).click();

  // The printhead back: the app finds it answering, and the dry run is green again.
  await missing.uncheck();
  await expect(page.getByTestId('faults')).toHaveCount(0, { timeout: 15_000 });
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await expect(dialog.locator('li[data-level="ok"]').first()).toHaveText('machine: the printhead answers, and the machine reports no fault');
  await expect(dialog.getByRole('button', { name: 'Expose now' })).toBeVisible();
  await dialog.screenshot({ path: info.outputPath('dry-run-printhead-back.png') });
  await dialog.getByRole('button', { name: 'Cancel' }).click();
});

test('item 4: paused to cool, Continue stays closed while the head is hot, and says so; Continue paced is open and says it waits to cool; the fault goes when the job goes on', async ({ page }, info) => {
  test.setTimeout(120_000);
  await open(page, 2);
  await startTestPattern(page, '100');
  await setLimits(page, { 4: 20, 5: 20 }); // below the room's 22 °C: T4 and T5 are over at once
  const hint = page.getByTestId('cool-hint');
  await expect(hint).toContainText('Paused to cool: the head reached a soft limit', { timeout: 30_000 });
  await expect(page.getByTestId('faults')).toContainText(/E31 over-temperature T4 [\d.]+ °C \(soft limit\)/);
  await expect(hint).toContainText(/, and T4 [\d.]+ °C \(limit 20 °C\), T5 [\d.]+ °C \(limit 20 °C\) are still too hot\./);
  const cont = job(page).getByRole('button', { name: 'Continue', exact: true });
  await expect(cont).toBeDisabled();
  await expect(cont).toHaveAttribute('title', /^T4 .*, T5 .* are still too hot$/);
  await expect(page.getByTestId('continue-why')).toContainText('Continue: not yet, T4');
  await expect(hint.getByRole('button', { name: 'Continue paced' })).toBeEnabled(); // the Mega waits for the head to cool first
  await expect(page.getByTestId('continue-paced-waits')).toHaveText('waits for the head to cool, then continues');
  await page.screenshot({ path: info.outputPath('hot-two-sensors.png'), fullPage: true });

  await setLimits(page, { 4: 50 }); // one sensor left over its limit
  await expect(hint).toContainText(/, and T5 [\d.]+ °C \(limit 20 °C\) is still too hot\./);
  await expect(cont).toHaveAttribute('title', /^T5 [\d.]+ °C \(limit 20 °C\) is still too hot$/);
  await hint.screenshot({ path: info.outputPath('hot-one-sensor.png') });

  await setLimits(page, { 5: 50 }); // cooled, as far as the limits go
  await expect(cont).toBeEnabled();
  await expect(page.getByTestId('continue-paced-waits')).toBeHidden();
  await expect(page.getByTestId('faults')).toContainText('E31'); // it stands until the job goes on
  await hint.getByRole('button', { name: 'Continue paced' }).click();
  await expect(page.getByTestId('job-state')).toContainText('running, paced');
  await expect(page.getByTestId('faults')).toHaveCount(0);
  await page.screenshot({ path: info.outputPath('continued-paced.png'), fullPage: true });
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
  await expect(page.getByTestId('faults')).toHaveCount(0);
  await page.getByRole('tab', { name: 'LEDs & link' }).click();
  await expect(page.getByTestId('fault-log')).toContainText('E31 over-temperature T4'); // the log keeps it
});

test("item 4: the thermal warning gives the LEDs' duty a unit", async ({ page }, info) => {
  await open(page, 4);
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByLabel('Extra heating (°C/s)').fill('1');
  await page.getByRole('tab', { name: 'Thermal' }).click();
  const warning = page.getByTestId('thermal-warning').first();
  await expect(warning).toContainText(/is rising \d+ °C a minute; the LEDs' duty explains\s+\d+ °C a minute\. Check its fan and heatsink\./, { timeout: 30_000 });
  await warning.screenshot({ path: info.outputPath('thermal-warning.png') });
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByRole('button', { name: 'Clear faults' }).click();
});

test('item 1: a paced job waiting to cool keeps every control but Pause and Stop closed', async ({ page }, info) => {
  test.setTimeout(120_000);
  await open(page, 2);
  await drawFilledRectangle(page, [0.3, 0.3], [0.32, 0.32]);
  await startTestPattern(page, '100');
  await job(page).getByRole('button', { name: 'Pause', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'paused');
  await typeLine(page, 'M850 thermal.limit.5 24'); // T5 reads 22.6: within 2 °C, and never 3 °C below
  await typeLine(page, 'M24 P1');
  await expect(page.getByTestId('job-state')).toContainText('running, paced, waiting for the head to cool', { timeout: 15_000 });
  await expectControls(page, info, 'cooling', allClosed(/a job is running \(waiting for the head to cool\)/, { Pause: true, Stop: true, Continue: /the job is running/ }));
  await typeLine(page, 'M850 thermal.limit.5 50');
  await expect(page.getByTestId('job-state')).not.toContainText('waiting for the head to cool', { timeout: 15_000 });
  await job(page).getByRole('button', { name: 'Stop', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'aborted');
});

test('item 5: a paced job is told in its paced times, as the question promised', async ({ page }, info) => {
  test.setTimeout(150_000);
  await open(page, 40);
  await drawFilledRectangle(page, [0.4, 0.4], [0.412, 0.412]); // as pacing.spec.ts: it would pause to cool
  await page.getByLabel('Full dose').fill('800');
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  const hmsS = (t: string) => t.split(':').map(Number).reduce((a, n) => a * 60 + n, 0);
  const pacedS = hmsS(/about (\d:\d\d:\d\d) in all/.exec((await dialog.getByTestId('paced-offer').textContent()) ?? '')![1]);
  const plainS = hmsS(/About (\d:\d\d:\d\d) of exposing/.exec((await dialog.getByTestId('confirm-estimate').textContent()) ?? '')![1]);
  expect(pacedS).toBeGreaterThan(plainS);
  await dialog.getByRole('button', { name: 'Expose paced' }).click();

  const eta = page.getByTestId('eta');
  await expect(eta).toContainText(/left \(paced\)/, { timeout: 30_000 });
  const left = Number(await eta.getAttribute('data-left-s'));
  const remaining = Number(await eta.getAttribute('data-remaining-s'));
  expect(left).toBeGreaterThan(remaining); // the Mega's remaining foresees no waits; what is shown does
  expect(Math.abs(left / Math.max(remaining, 1) - pacedS / plainS)).toBeLessThan(0.05 * (pacedS / plainS) + 1 / Math.max(remaining, 1));
  await page.screenshot({ path: info.outputPath('paced-left.png'), fullPage: true });

  const took = page.getByTestId('job-took');
  await expect(took).toBeVisible({ timeout: 120_000 });
  expect(Math.abs(Number(await took.getAttribute('data-estimate-us')) / 1e6 - pacedS)).toBeLessThanOrEqual(1);
  await took.screenshot({ path: info.outputPath('paced-took.png') });
});
