// Issue 17, item 6: when a job ends, a person in another room notices: a desktop notification
// (the permission asked from the click that started the job) and the page's title.
import { expect, test } from '@playwright/test';

test('a finished job says so in a desktop notification and in the title', async ({ page }, info) => {
  test.setTimeout(120_000); // a whole job, upload to end, as the other job specs allow
  // The desktop as the page sees it: a Notification that records what it was asked to show, and a
  // user who answers "Allow" when asked.
  await page.addInitScript(() => {
    const shown: { title: string; body?: string }[] = [];
    let permission: NotificationPermission = 'default';
    class RecordedNotification {
      static get permission() {
        return permission;
      }
      static async requestPermission() {
        permission = 'granted';
        return permission;
      }
      constructor(title: string, options?: NotificationOptions) {
        shown.push({ title, body: options?.body });
      }
    }
    Object.defineProperty(window, 'Notification', { value: RecordedNotification });
    Object.defineProperty(window, '__notifications', { value: shown });
  });
  await page.setViewportSize({ width: 1440, height: 900 });
  // Slow enough, and a long enough dose, that the job runs for seconds: the title is seen mid-job.
  await page.goto('/?simSpeed=10');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page).toHaveTitle('UV Exposure');
  await page.getByLabel('Full dose').fill('20');
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('button', { name: 'Expose now' }).click(); // item 4's confirmation (it loads on demand: wait for it)
  await expect(page).toHaveTitle(/% exposing · UV Exposure$/, { timeout: 30_000 });
  // The user looks away: another window has the focus.
  await page.evaluate(() => window.dispatchEvent(new Event('blur')));
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
  const shown = await page.evaluate(() => (window as unknown as { __notifications: { title: string; body?: string }[] }).__notifications);
  expect(shown).toEqual([{ title: 'Job done', body: expect.stringMatching(/: done, stop (\d+) of \1\.$/) }]);
  await expect(page).toHaveTitle('Job done · UV Exposure');
  await page.screenshot({ path: info.outputPath('job-done.png') });
});
