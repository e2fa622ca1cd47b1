// Job control on the simulated printer: framing with the LEDs off, and resuming a job that a
// restart interrupted (reopening the link restarts the machine, as a real Mega's USB port does).
import { expect, test, type Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';

/** Unplug and plug in again: the simulated Mega restarts, as a real one does when its USB port opens. */
async function reconnect(page: Page) {
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
}

/** A dose long enough that the test pattern outlasts a reconnect (the printer runs on while the link is closed). */
const LONG_DOSE_MS = '40';

test('a job interrupted by a restart is offered for resume on connect, and runs to its end', async ({ page }, info) => {
  await page.goto('/?simSpeed=4');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
  await page.getByTestId('full-ms').fill(LONG_DOSE_MS);
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByTestId('start-test').click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
  await expect(page.getByTestId('job-state')).toContainText(/running: stop ([1-9]\d*) of/, { timeout: 30_000 });
  await expect(page.getByTestId('eta')).toContainText(/left, done at about/);
  await page.screenshot({ path: info.outputPath('running.png'), fullPage: true });

  await reconnect(page); // the card holds the checkpoint
  const offer = page.getByTestId('resume-offer');
  await expect(offer).toContainText(/test-pattern-1\.uvj.*: [1-9]\d* of \d+ stops are done/);
  await page.screenshot({ path: info.outputPath('offer.png'), fullPage: true });
  await page.getByTestId('resume-job').click();
  await expect(offer).toHaveCount(0);
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
  await expect(page.getByTestId('console-log')).toContainText('echo:resume: stop');
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
  await expect(page.getByTestId('job-state')).toContainText(/done: stop (\d+) of \1/);

  // Nothing is left to resume.
  await reconnect(page);
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
});

test('a discarded interrupted job is not offered again', async ({ page }) => {
  await page.goto('/?simSpeed=4');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('full-ms').fill(LONG_DOSE_MS);
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByTestId('start-test').click();
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]/, { timeout: 30_000 });
  await reconnect(page);
  await page.getByTestId('discard-job').click();
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
  await reconnect(page);
  await expect(page.getByTestId('resume-offer')).toHaveCount(0);
});

test('framing takes the head round the drawing with the LEDs off, and ends where it began', async ({ page }) => {
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('frame')).toBeDisabled(); // nothing drawn
  await drawFilledRectangle(page, [0.4, 0.4], [0.45, 0.45]);
  await page.getByTestId('tab-position').click();
  await page.getByTestId('frame').click();
  // Not homed yet: it says so and homes only when the user agrees.
  await expect(page.getByRole('dialog')).toContainText('Frame: home the machine first?');
  await page.getByRole('dialog').getByRole('button', { name: 'Home and continue' }).click();
  const log = page.getByTestId('console-log');
  await expect(log).toContainText('G28', { timeout: 30_000 });
  // Five moves: four corners and back to the first (a move refused for want of homing is sent again).
  const corners = page.getByTestId('console-log').locator('li', { hasText: /> G0 X/ });
  const sent = async () => (await corners.allTextContents()).map((l) => l.split('> ')[1]);
  await expect.poll(async () => { const t = await sent(); return new Set(t).size === 4 && t.length >= 5 && t.at(-1) === t[0]; }, { timeout: 30_000 }).toBe(true);
  const moves = (await corners.allTextContents()).slice(-5).map((t) => /X([\d.]+) Y([\d.]+)/.exec(t)!.slice(1).map(Number));
  expect(moves[4]).toEqual(moves[0]);
  expect(new Set(moves.map((m) => m[0])).size).toBe(2); // a rectangle: two Xs, two Ys
  expect(new Set(moves.map((m) => m[1])).size).toBe(2);
  await expect(page.getByTestId('position')).toContainText(`X ${moves[0][0].toFixed(3)} Y ${moves[0][1].toFixed(3)}`, { timeout: 30_000 });
  await page.getByTestId('tab-link').click();
  await expect(page.getByTestId('led-state')).toHaveAttribute('data-lit', 'false');
});
