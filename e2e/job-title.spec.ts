// Issue 41 item 6: the guide says the page's title shows a job's progress and its end. Proven on the
// simulated printer with the page in front of the user: the progress as the job runs, then the end,
// which stays in the title as long as the job's line shows it (a stopped job says so too).
import { expect, test, type Page } from '@playwright/test';

/** Every title the page takes, in order, from now on. */
async function recordTitles(page: Page) {
  await page.evaluate(() => {
    const seen: string[] = [document.title];
    (window as unknown as { __titles: string[] }).__titles = seen;
    new MutationObserver(() => {
      if (seen.at(-1) !== document.title) seen.push(document.title);
    }).observe(document.head, { subtree: true, childList: true, characterData: true });
  });
}
const titles = (page: Page) => page.evaluate(() => (window as unknown as { __titles: string[] }).__titles);

test('the title shows a scan job’s progress, then its end, while the page is looked at', async ({ page }, info) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=10');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page).toHaveTitle('UV Exposure');
  await recordTitles(page);
  await page.getByLabel('Full dose').fill('20');
  await page.getByRole('button', { name: 'Expose test pattern' }).click(); // automatic: a scan on the move
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  // The progress is read from the titles recorded all along: a loaded machine may run the short job
  // between two polls of the page.
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
  expect(await page.evaluate(() => document.hasFocus() && document.visibilityState === 'visible')).toBe(true);
  await expect(page).toHaveTitle('Job done · UV Exposure');
  await page.getByTestId('job-state').screenshot({ path: info.outputPath('job-done-line.png') });

  // The progress rose through the job, and the end followed it.
  const seen = await titles(page);
  const percents = seen.map((t) => /^(\d+) % exposing/.exec(t)?.[1]).filter((p) => p !== undefined).map(Number);
  expect(percents.length, seen.join(' | ')).toBeGreaterThanOrEqual(3);
  expect(percents).toEqual([...percents].sort((a, b) => a - b));
  expect(seen.at(-1)).toBe('Job done · UV Exposure');

  // Still said a while later, the page looked at all along, as the job's line still says it.
  await page.waitForTimeout(3000);
  await expect(page).toHaveTitle('Job done · UV Exposure');

  // A job stopped by the user: the title says it was stopped.
  await page.getByTestId('strategy').selectOption('serpentine');
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  await expect(page).toHaveTitle(/^\d+ % exposing · UV Exposure$/, { timeout: 30_000 });
  await page.getByRole('button', { name: 'Stop', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'aborted', { timeout: 30_000 });
  await expect(page).toHaveTitle('Job stopped · UV Exposure');
  await page.screenshot({ path: info.outputPath('job-stopped.png') });
});
