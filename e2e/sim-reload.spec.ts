// Issue 17, item 5: the simulated printer across a page reload behaves as a real printer across a
// reconnect. Its card, checkpoint and saved settings are kept in the browser; a reload asks first
// while a job runs, finds the job run on meanwhile and offers to resume it. Disconnecting mid-job
// says the printer may still be exposing.
import { expect, test, type Page } from '@playwright/test';

/**
 * A test pattern with a long enough dose that it outlasts a reload: a printer that runs on while the
 * page is away would finish a short job meanwhile, and there would be nothing to resume.
 */
async function startTestPattern(page: Page) {
  await page.getByLabel('Full dose').fill('40');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click();
}

/** The stop the Job panel shows the job at. */
async function stopShown(page: Page): Promise<number> {
  const text = (await page.getByTestId('job-state').textContent()) ?? '';
  return Number(/stop (\d+) of/.exec(text)?.[1]);
}

async function typeLine(page: Page, line: string) {
  const input = page.getByRole('textbox', { name: 'A line for the printer' });
  await input.fill(line);
  await input.press('Enter');
}

test('a reload mid-job asks first, then offers the job, run on meanwhile, for resuming, and it runs to its end', async ({ page }, info) => {
  test.setTimeout(120_000);
  await page.goto('/?simSpeed=2');
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await startTestPattern(page);
  await expect(page.getByTestId('job-state')).toContainText(/running: stop ([1-9]\d*) of/, { timeout: 30_000 });
  await page.screenshot({ path: info.outputPath('1-running.png'), fullPage: true });
  const before = await stopShown(page);

  // The browser asks before the page goes while a job runs; the user says "Reload".
  const asked: string[] = [];
  page.once('dialog', (d) => {
    asked.push(d.type());
    void d.accept();
  });
  await page.reload();
  expect(asked).toEqual(['beforeunload']);

  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  const offer = page.getByTestId('resume-offer');
  await expect(offer).toContainText(/The printer restarted while exposing test-pattern-1\.uvj: (\d+) of (\d+) stops are done/);
  const done = Number(/: (\d+) of/.exec((await offer.textContent()) ?? '')?.[1]);
  expect(done).toBeGreaterThanOrEqual(before); // it ran on while the page was away
  await expect(page.getByTestId('simulator-note')).toHaveCount(0); // kept, nothing lost
  await page.screenshot({ path: info.outputPath('2-offer-after-reload.png'), fullPage: true });

  await offer.getByRole('button', { name: 'Resume' }).click();
  await expect(offer).toHaveCount(0);
  await expect(page.getByTestId('console-log')).toContainText('echo:resume: stop');
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 90_000 });
  await expect(page.getByTestId('job-state')).toContainText(/done: stop (\d+) of \1/);
  await page.screenshot({ path: info.outputPath('3-resumed-done.png'), fullPage: true });

  // Done: a reload now neither asks nor offers anything.
  page.once('dialog', (d) => {
    asked.push(d.type());
    void d.accept();
  });
  await page.reload();
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await expect(page.getByTestId('job-state')).toContainText('No job.');
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
  expect(asked).toEqual(['beforeunload']);
});

test('disconnecting mid-job says the printer may still be exposing, and connecting again offers the job', async ({ page }, info) => {
  await page.goto('/?simSpeed=2');
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await startTestPattern(page);
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of/, { timeout: 30_000 });
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await expect(page.getByTestId('connection')).toContainText('Not connected.');
  await expect(page.getByTestId('lost-job')).toContainText(/The job was running at stop \d+ of \d+ when the link was closed;\s+the printer may still be exposing/);
  await expect(page.getByTestId('job-state')).toContainText('Not connected: the job may still be running on the printer');
  await expect(page.getByTestId('job-state')).not.toContainText('No job.');
  await page.screenshot({ path: info.outputPath('disconnected-mid-job.png'), fullPage: true });
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('resume-offer')).toContainText(/test-pattern-1\.uvj: \d+ of \d+ stops are done/);
  await expect(page.getByTestId('lost-job')).toHaveCount(0);
});

test('settings saved with M500 and the files on the card survive a reload; settings not saved do not', async ({ page }, info) => {
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  const log = page.getByTestId('console-log');
  await typeLine(page, 'M850 speed.travel 120');
  await typeLine(page, 'M500');
  await expect(log).toContainText('echo:Settings stored');
  await typeLine(page, 'M850 accel.x 2500');
  await expect(log.locator('li', { hasText: '> M850 accel.x 2500' })).toHaveCount(1);
  await page.reload(); // no job: nothing to ask
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await typeLine(page, 'M850 speed.travel');
  await expect(log).toContainText('M850 speed.travel 120');
  await typeLine(page, 'M850 accel.x');
  await expect(log).toContainText('M850 accel.x 2000');
  await typeLine(page, 'M20');
  await expect(log).toContainText('CONFIG.TXT');
  await page.screenshot({ path: info.outputPath('settings-after-reload.png'), fullPage: true });
});

test('a damaged store starts a clean printer, and the page says what was lost', async ({ page }, info) => {
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  // What a broken write or another version might leave: a card that is no list, a record of another version.
  await page.evaluate(
    () =>
      new Promise<void>((resolve, reject) => {
        const open = indexedDB.open('uv-exposure-sim');
        open.onerror = () => reject(open.error);
        open.onsuccess = () => {
          const tx = open.result.transaction('printer', 'readwrite');
          tx.objectStore('printer').put('not a card', 'card');
          tx.objectStore('printer').put({ version: 99 }, 'machine');
          tx.oncomplete = () => resolve();
          tx.onerror = () => reject(tx.error);
        };
      }),
  );
  await page.reload();
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  const note = page.getByTestId('simulator-note');
  await expect(note).toContainText('The simulated printer kept in this browser was damaged: its card could not be read, so the card is empty');
  await expect(note).toContainText('its settings and checkpoint could not be read, so it has its defaults and nothing to resume');
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
  await page.screenshot({ path: info.outputPath('damaged-store.png'), fullPage: true });
  // The clean printer is kept again: the next reload has nothing to say.
  await typeLine(page, 'M500');
  await expect(page.getByTestId('console-log')).toContainText('echo:Settings stored');
  await page.reload();
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await expect(page.getByTestId('simulator-note')).toHaveCount(0);
});

test('a second tab has a printer of its own, and says that a reload does not keep it', async ({ page, context }, info) => {
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
  const second = await context.newPage();
  await second.goto('/?simSpeed=20');
  await expect(second.getByTestId('connection')).toContainText('Connected to the simulated printer');
  await expect(second.getByTestId('simulator-note')).toContainText('Another tab has the simulated printer');
  await expect(page.getByTestId('simulator-note')).toHaveCount(0);
  await second.screenshot({ path: info.outputPath('second-tab.png'), fullPage: true });
  await second.close();
});
