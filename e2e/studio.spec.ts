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
  // The dry run came first: on the bed, within the printhead's cap and the thermal budget.
  const checks = page.getByTestId('dry-run').locator('li');
  await expect(checks).toHaveCount(3);
  for (const level of await checks.evaluateAll((li) => li.map((l) => l.getAttribute('data-level')))) expect(level).toBe('ok');
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
  // Wide enough to show at this zoom: a coarse view keeps a cell's darkest neighbour, so thin gaps close.
  await page.getByTestId('tool-size').fill('120');
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

/** A BMP of w × h pixels, black on its left half and white on its right (24-bit, bottom-up rows). */
function halfBlackBmp(w: number, h: number): Buffer {
  const row = Math.ceil((w * 3) / 4) * 4;
  const b = Buffer.alloc(54 + row * h);
  b.write('BM', 0);
  b.writeUInt32LE(b.length, 2);
  b.writeUInt32LE(54, 10);
  b.writeUInt32LE(40, 14);
  b.writeInt32LE(w, 18);
  b.writeInt32LE(h, 22);
  b.writeUInt16LE(1, 26);
  b.writeUInt16LE(24, 28);
  b.writeUInt32LE(row * h, 34);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) b.fill(x < w / 2 ? 0 : 255, 54 + y * row + x * 3, 54 + y * row + x * 3 + 3);
  return b;
}

test('imports a picture at a physical size, dithered, and places it where the view is', async ({ page }, info) => {
  await page.goto('/?simSpeed=40');
  await page.getByTestId('import-file').setInputFiles({ name: 'half.bmp', mimeType: 'image/bmp', buffer: halfBlackBmp(40, 20) });
  await page.getByTestId('import-width').fill('10');
  await expect(page.getByTestId('import-size')).toHaveText(/^200 × 100 cells, 5\.0 mm high$/);
  await page.getByTestId('import-halftone').selectOption('threshold');
  await expect(page.getByTestId('import-preview')).toBeVisible();
  await page.getByTestId('import-place').click();
  const box = (await page.getByTestId('editor-canvas').boundingBox())!;
  // The picture sits in the middle of the view: its black half left of centre, its white half right.
  const centreX = 22 + (box.width - 22) / 2, centreY = 22 + (box.height - 22) / 2;
  await expect.poll(() => pixel(page, centreX - 8, centreY).then(isDose)).toBe(true);
  expect(isDose(await pixel(page, centreX + 8, centreY))).toBe(false);
  await page.screenshot({ path: info.outputPath('imported.png'), fullPage: true });
  await page.getByTestId('undo').click();
  await expect.poll(() => pixel(page, centreX - 8, centreY).then(isDose)).toBe(false);
  // Inverted, the white half is the one exposed.
  await page.getByTestId('import-invert').check();
  await page.getByTestId('import-place').click();
  await expect.poll(() => pixel(page, centreX + 8, centreY).then(isDose)).toBe(true);
  expect(isDose(await pixel(page, centreX - 8, centreY))).toBe(false);
});

test('a file that is not a picture says so', async ({ page }) => {
  await page.goto('/?simSpeed=40');
  await page.getByTestId('import-file').setInputFiles({ name: 'notes.png', mimeType: 'image/png', buffer: Buffer.from('not a png at all') });
  await expect(page.getByTestId('import-error')).toContainText('not a picture');
});
