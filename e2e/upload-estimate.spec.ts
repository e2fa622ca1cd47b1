// Issue 41, item 5: the upload is in the estimate and in the progress. A 30 × 30 mm filled rectangle on
// the simulated printer (the firmware as WebAssembly, which reads job format 2): the question names the
// upload's time, bytes and rate before "of exposing", and the sum; the Job panel says "Uploading the job:
// N %" with the time left while the bytes go, then the exposure runs; the next question uses the rate
// measured on that upload.
import { expect, test } from '@playwright/test';
import { drawFilledRectangle } from './draw';

test('the question and the progress name the upload, at the line rate and then at the measured one', async ({ page }, info) => {
  test.setTimeout(180_000);
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto('/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  // 30 × 30 mm from (40, 40) mm: the bed, 200 mm, spans these shares of the canvas at its fit.
  const x = (mm: number) => 0.2033 + (mm / 200) * 0.5934;
  const y = (mm: number) => 0.0266 + (mm / 200) * 0.9449;
  await drawFilledRectangle(page, [x(40), y(40)], [x(70), y(70)]);
  await page.getByTestId('strategy').selectOption('serpentine');
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  await expect(dialog.getByRole('button', { name: /Expose (now|anyway)/ })).toBeVisible({ timeout: 90_000 });
  const upload = /First the job is uploaded: about (\d+):(\d\d):(\d\d) for ([\d.]+) KB at 11\.5 KB\/s, the line's rate \(no upload measured yet\), its rows run-length coded\./;
  await expect(dialog).toContainText(upload);
  await expect(dialog).toContainText(/About \d+:\d\d:\d\d of exposing/);
  const text = (await dialog.textContent()) ?? '';
  const [, h, m, s, kb] = upload.exec(text)!;
  const uploadS = Number(h) * 3600 + Number(m) * 60 + Number(s);
  // Run-length rows: some 600 records of a filled row each, about 20 KB on the wire where hex rows were about 1 MB.
  expect(Number(kb)).toBeGreaterThan(10);
  expect(Number(kb)).toBeLessThan(40);
  expect(uploadS).toBeGreaterThanOrEqual(1);
  expect(uploadS).toBeLessThanOrEqual(4);
  const [, eh, em, es] = /About (\d+):(\d\d):(\d\d) of exposing/.exec(text)!;
  const [, th, tm, ts] = /About (\d+):(\d\d):(\d\d) in all\./.exec(text)!;
  const hmsS = (a: string, b: string, c: string) => Number(a) * 3600 + Number(b) * 60 + Number(c);
  expect(Math.abs(hmsS(th, tm, ts) - (hmsS(eh, em, es) + uploadS))).toBeLessThanOrEqual(1);
  await dialog.screenshot({ path: info.outputPath('question-line-rate.png') });

  // The page's main thread busy 40 ms of every 100, as a laptop doing other work: the upload lasts a few seconds.
  await page.evaluate(() => {
    setInterval(() => {
      const until = performance.now() + 40;
      while (performance.now() < until) {
        // busy
      }
    }, 100);
  });
  await dialog.getByRole('button', { name: /Expose (now|anyway)/ }).click();
  const progress = page.getByRole('status', { name: 'Upload' });
  await expect(progress).toContainText(/Uploading the job: \d+ %.*; then the exposure starts\./, { timeout: 30_000 });
  await expect(progress.getByRole('progressbar', { name: 'Upload progress' })).toBeVisible();
  await page.getByRole('region', { name: 'Job' }).screenshot({ path: info.outputPath('uploading.png') });
  await expect(progress).toContainText(/about \d+ s left at [\d.]+ KB\/s/, { timeout: 30_000 });
  const state = page.getByTestId('job-state');
  await expect(state).toContainText(/running/, { timeout: 60_000 });
  await expect(progress).toBeHidden();
  await page.getByRole('region', { name: 'Job' }).screenshot({ path: info.outputPath('exposing.png') });
  await page.getByRole('button', { name: 'Stop' }).click();
  await expect(state).toHaveAttribute('data-state', /aborted|idle/, { timeout: 30_000 });

  // Asked again, the question uses the rate this link measured on that upload.
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await expect(dialog.getByRole('button', { name: /Expose (now|anyway)/ })).toBeVisible({ timeout: 90_000 });
  await expect(dialog).toContainText(/First the job is uploaded: about \d+:\d\d:\d\d for [\d.]+ KB at [\d.]+ KB\/s, as measured on the last upload, its rows run-length coded\./);
  await dialog.screenshot({ path: info.outputPath('question-measured-rate.png') });
  await dialog.getByRole('button', { name: 'Cancel' }).click();
});

test('a small job says its upload takes under a second', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the test pattern?' });
  await expect(dialog).toContainText(/First the job is uploaded: in under a second for [\d.]+ (KB|bytes) at 11\.5 KB\/s, the line's rate \(no upload measured yet\)/);
  await expect(dialog).toContainText(/About \d:\d\d:\d\d in all\./);
  await dialog.screenshot({ path: info.outputPath('test-pattern-question.png') });
  await dialog.getByRole('button', { name: 'Cancel' }).click();
});
