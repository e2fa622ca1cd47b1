// Issue 29, item 11: the console kept one bound for all its lines, and the hidden auto-reports
// pushed out everything else: after an hour's job it was empty, the fault included. What the
// person typed, the replies and every fault stay, however many reports come after them.
import { expect, test } from '@playwright/test';

test('what was typed, its reply and the fault stay in the console through thousands of auto-reports', async ({ page }, info) => {
  test.setTimeout(180_000);
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto('/?simSpeed=100'); // a second of the test is 100 of the printer's: three reports each, and their oks
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const consoleRegion = page.getByRole('region', { name: 'Console' });
  const input = consoleRegion.getByRole('textbox', { name: 'A line for the printer' });
  const log = consoleRegion.getByRole('list');

  await input.fill('M115');
  await input.press('Enter');
  await expect(log.getByRole('listitem').filter({ hasText: /> M115$/ })).toBeVisible();
  await input.fill('M105');
  await input.press('Enter');
  await expect(log.getByRole('listitem').filter({ hasText: /T:\d+\.\d \/\d+\.\d S0:/ })).toHaveCount(1); // its reply
  const reply = (await log.getByRole('listitem').filter({ hasText: /T:\d+\.\d \/\d+\.\d S0:/ }).textContent())!.replace(/^\S+ /, '');

  // A fault: the printhead stops answering, and comes back.
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' }).check();
  await expect(log.getByRole('listitem').filter({ hasText: 'E30' }).first()).toBeVisible({ timeout: 30_000 });
  await page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' }).uncheck();
  await expect(page.getByTestId('faults')).toHaveCount(0, { timeout: 30_000 });
  const shownBefore = await log.getByRole('listitem').allTextContents();
  const fault = shownBefore.find((l) => /E30/.test(l))!;

  // Then the printer reports on: five times the lines the old single bound of 2000 kept.
  const logged = async () => Number(await log.getAttribute('data-logged'));
  const from = await logged();
  await expect.poll(logged, { timeout: 150_000, intervals: [2000] }).toBeGreaterThan(from + 10_000);

  await expect(log.getByRole('listitem').filter({ hasText: /> M115$/ })).toHaveCount(1);
  await expect(log.getByRole('listitem').filter({ hasText: /> M105$/ })).toHaveCount(1);
  await expect(log.getByRole('listitem').filter({ hasText: reply })).toHaveCount(1);
  await expect(log.getByRole('listitem').filter({ hasText: fault.replace(/^\S+ /, '') }).first()).toBeVisible();
  expect(await log.getByRole('listitem').allTextContents()).toEqual(expect.arrayContaining(shownBefore));
  await consoleRegion.screenshot({ path: info.outputPath('console-after-reports.png') });
  // Scrolled up to read the history, it stays there while the hidden reports come in.
  await log.evaluate((ol) => ol.scrollTo({ top: 0 }));
  await page.waitForTimeout(1500); // at 100×, 150 reports and more come in meanwhile
  expect(await log.evaluate((ol) => ol.scrollTop)).toBe(0);
  await consoleRegion.screenshot({ path: info.outputPath('console-scrolled-up.png') });
  // The reports themselves are there when asked for, the newest of them.
  await consoleRegion.getByLabel('reports').check();
  await expect.poll(() => log.getByRole('listitem').filter({ hasText: /^\S+ T:/ }).count()).toBeGreaterThan(50);
  await consoleRegion.screenshot({ path: info.outputPath('console-with-reports.png') });
});
