// The exposure preview of a drawing: the plan's light, stops and travel, time and LED shares,
// scrubbed and stepped through.
import { expect, test, type Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';

/** How many of the preview canvas's pixels are lit (not the bed's near-white). */
const litPixels = (page: Page) =>
  page.getByTestId('preview-canvas').evaluate((c: HTMLCanvasElement) => {
    const d = c.getContext('2d')!.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i + 1] < 200 && d[i] > d[i + 1] + 20) n++; // violet, not grey travel
    return n;
  });

test('previews a drawing: time, stops, LEDs, and the light stop by stop', async ({ page }, info) => {
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('view-preview')).toBeDisabled(); // nothing drawn
  await drawFilledRectangle(page, [0.4, 0.4], [0.43, 0.42]);
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire: the light stop by stop

  await page.getByTestId('view-preview').click();
  await expect(page.getByTestId('preview-summary')).toContainText(/^\d+ stops in \d+ passes, about 0:\d\d:\d\d, \d+ mm of travel$/);
  const coverage = await page.getByTestId('preview-coverage').textContent();
  const cells = [...coverage!.matchAll(/LED \d: (\d+) cells/g)].map((m) => Number(m[1]));
  expect(cells).toHaveLength(4);
  expect(cells.every((n) => n > 0)).toBe(true); // adjacent rows: every LED takes a share
  const all = await litPixels(page);
  expect(all).toBeGreaterThan(100);
  await page.screenshot({ path: info.outputPath('preview.png'), fullPage: true });

  // Scrub to the start: nothing lit yet. Step on: the first stop, at its time.
  const stops = Number(/^(\d+) stops/.exec((await page.getByTestId('preview-summary').textContent())!)![1]);
  await page.getByTestId('preview-scrub').fill('0');
  await expect(page.getByTestId('preview-at')).toHaveText(`0 of ${stops} stops`);
  await expect.poll(() => litPixels(page)).toBe(0);
  await page.getByTestId('preview-next').click();
  await expect(page.getByTestId('preview-at')).toContainText(new RegExp(`^1 of ${stops} stops, 0:00:0\\d of 0:\\d\\d:\\d\\d$`)); // the travel to the job, then one exposure
  await page.getByTestId('preview-scrub').fill(String(Math.floor(stops / 2)));
  await expect.poll(() => litPixels(page)).toBeGreaterThan(0);
  expect(await litPixels(page)).toBeLessThan(all);
  await page.screenshot({ path: info.outputPath('scrubbed.png'), fullPage: true });

  // Play runs on to the end.
  await page.getByTestId('preview-play').click();
  await expect(page.getByTestId('preview-at')).toContainText(`${stops} of ${stops} stops`, { timeout: 20_000 });
  await page.getByTestId('preview-layer').selectOption('led');
  await page.screenshot({ path: info.outputPath('leds.png'), fullPage: true });

  // Back to drawing: the drawing is as it was.
  await page.getByTestId('view-draw').click();
  await expect(page.getByTestId('expose-drawing')).toBeEnabled();
});
