// The studio's grid editor in Chromium: draw, undo and redo, zoom and pan, and expose the drawing
// on the simulated printer.
import { expect, test, type Page } from '@playwright/test';

/** The colour the canvas shows at a point of its box (CSS pixels). */
async function pixel(page: Page, x: number, y: number): Promise<[number, number, number]> {
  return page.getByTestId('editor-canvas').evaluate((c: HTMLCanvasElement, [x, y]) => {
    const dpr = window.devicePixelRatio || 1;
    const d = c.getContext('2d')!.getImageData(Math.round(x * dpr), Math.round(y * dpr), 1, 1).data;
    return [d[0], d[1], d[2]] as [number, number, number];
  }, [x, y]);
}
const isDose = ([r, g]: number[]) => g < r - 15; // UV violet: neither the white bed nor the grey around it

test('draws a filled rectangle, undoes and redoes it, zooms, and exposes it', async ({ page }, info) => {
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const canvas = page.getByTestId('editor-canvas');
  const box = (await canvas.boundingBox())!;
  await expect(page.getByTestId('expose-drawing')).toBeDisabled(); // nothing drawn yet

  await page.getByTestId('tool-rect-filled').click();
  const a = { x: box.x + box.width * 0.3, y: box.y + box.height * 0.3 };
  const b = { x: box.x + box.width * 0.34, y: box.y + box.height * 0.35 }; // about 130 × 110 cells: a short job
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move(b.x, b.y, { steps: 5 });
  await page.mouse.up();
  const mid = { x: box.width * 0.32, y: box.height * 0.325 };
  await expect.poll(() => pixel(page, mid.x, mid.y).then(isDose)).toBe(true);
  await expect(page.getByTestId('expose-drawing')).toBeEnabled();
  await page.screenshot({ path: info.outputPath('drawn.png'), fullPage: true });

  await page.getByTestId('undo').click();
  await expect.poll(() => pixel(page, mid.x, mid.y).then(isDose)).toBe(false);
  await expect(page.getByTestId('expose-drawing')).toBeDisabled();
  await canvas.focus();
  await page.keyboard.press('Control+Shift+Z');
  await expect.poll(() => pixel(page, mid.x, mid.y).then(isDose)).toBe(true);

  // Zoom in on a corner of the rectangle with the wheel: the bed's white fills the view's other side.
  await page.mouse.move(a.x, a.y);
  for (let i = 0; i < 6; i++) await page.mouse.wheel(0, -240);
  await expect.poll(() => pixel(page, a.x - box.x + 20, a.y - box.y + 20).then(isDose)).toBe(true);
  await expect.poll(() => pixel(page, a.x - box.x - 40, a.y - box.y - 40).then(isDose)).toBe(false);
  await page.screenshot({ path: info.outputPath('zoomed.png'), fullPage: true });
  await page.keyboard.press('0'); // fit again

  await page.getByTestId('expose-drawing').click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });
  await page.screenshot({ path: info.outputPath('exposed.png'), fullPage: true });
});

test('brush, eraser and fill paint at the dose picked', async ({ page }) => {
  await page.goto('/?simSpeed=40');
  const canvas = page.getByTestId('editor-canvas');
  const box = (await canvas.boundingBox())!;
  await page.getByTestId('tool-size').fill('20');
  await page.getByTestId('tool-dose').fill('128');
  await expect(page.getByTestId('tool-dose-value')).toHaveText('50 %');
  const y = box.y + box.height / 2;
  await page.mouse.move(box.x + box.width * 0.2, y);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.8, y, { steps: 10 });
  await page.mouse.up();
  const stroke = await pixel(page, box.width / 2, box.height / 2);
  expect(isDose(stroke)).toBe(true);
  const full = [74, 20, 140];
  expect(stroke[0]).toBeGreaterThan(full[0] + 40); // half the dose: a lighter violet than full
  await page.getByTestId('tool-eraser').click();
  await page.mouse.move(box.x + box.width / 2, y - 40);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2, y + 40, { steps: 5 });
  await page.mouse.up();
  await expect.poll(() => pixel(page, box.width / 2, box.height / 2).then(isDose)).toBe(false);
  expect(isDose(await pixel(page, box.width * 0.3, box.height / 2))).toBe(true);
  await page.getByTestId('tool-fill').click();
  await page.getByTestId('tool-dose').fill('255');
  await page.mouse.click(box.x + box.width * 0.5, box.y + 60); // the empty bed above the stroke
  await expect.poll(() => pixel(page, box.width * 0.5, 60).then(isDose)).toBe(true);
  await expect.poll(() => pixel(page, 5, box.height - 5).then(isDose)).toBe(false); // the fill stays on the bed
});
