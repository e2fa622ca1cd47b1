// Issue 29, item 14, in the studio: a 600-dpi picture reads 600 DPI; Ctrl+Z undoes after a toolbar
// click; an import lands on no older object; new text at the overview's zoom is not hidden under its
// handles; the dry run counts stops from 1.
import { expect, test, type Page } from '@playwright/test';
import { bmpFile, halfBlack, pngFile } from '../app/src/studio/image/picture-files.fixture';
import { bedPoint } from './canvas';
import { drawFilledRectangle } from './draw';

async function open(page: Page, speed = 40) {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto(`/?simSpeed=${speed}`);
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
}

const importer = (page: Page) => page.getByLabel('Import artwork (SVG, PNG, JPG, BMP, GIF)');
const selected = (page: Page) => page.getByRole('region', { name: 'Selected object' });
type Box = { x: number; y: number; w: number; h: number };
const overlap = (a: Box, b: Box) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;

/** The selected object's place and size, mm, as its panel shows them. */
async function boxOf(page: Page): Promise<Box> {
  const field = async (name: string) => Number(await page.getByTestId(`object-${name}`).inputValue());
  return { x: await field('x'), y: await field('y'), w: await field('w'), h: await field('h') };
}

test('a 600-dpi PNG reads 600 DPI', async ({ page }, info) => {
  await open(page);
  // 709 × 472 pixels at 23 622 a metre, as image editors write 600 dpi: 30 × 20 mm.
  const png = Buffer.from(pngFile(709, 472, halfBlack(709), { pixelsPerMetre: { x: 23622, y: 23622 } }));
  await importer(page).setInputFiles({ name: 'board-600.png', mimeType: 'image/png', buffer: png });
  await expect(selected(page)).toContainText('board-600.png');
  await expect(selected(page).getByLabel('Resolution')).toHaveValue('600');
  await selected(page).screenshot({ path: info.outputPath('resolution-600.png') });
});

test('Ctrl+Z undoes with the focus on a toolbar button', async ({ page }, info) => {
  await open(page);
  const tools = page.getByRole('toolbar', { name: 'Tools' });
  await drawFilledRectangle(page, [0.3, 0.3], [0.4, 0.4]);
  await expect(tools.getByRole('button', { name: 'Undo' })).toBeEnabled();
  await tools.getByRole('button', { name: 'Brush' }).click(); // the focus stays on the button
  await expect(tools.getByRole('button', { name: 'Brush' })).toBeFocused();
  await page.keyboard.press('Control+z');
  await expect(tools.getByRole('button', { name: 'Undo' })).toBeDisabled();
  await expect(tools.getByRole('button', { name: 'Redo' })).toBeEnabled();
  await expect(page.getByRole('button', { name: 'Expose drawing' })).toHaveAttribute('title', /nothing is drawn/);
  await page.keyboard.press('Control+Shift+Z');
  await expect(tools.getByRole('button', { name: 'Redo' })).toBeDisabled();
  // The question before an exposure holds the job it asks about: Ctrl+Z there leaves the drawing alone.
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await expect(page.getByRole('dialog')).toBeVisible();
  await page.keyboard.press('Control+z');
  await page.getByRole('dialog').getByRole('button', { name: 'Cancel' }).click();
  await expect(tools.getByRole('button', { name: 'Redo' })).toBeDisabled();
  // A field that takes text keeps Ctrl+Z for itself.
  await tools.getByLabel('Size').fill('7');
  await page.keyboard.press('Control+z');
  await expect(tools.getByRole('button', { name: 'Redo' })).toBeDisabled();
  // And from a button again, it undoes.
  await tools.getByRole('button', { name: 'Eraser' }).click();
  await page.keyboard.press('Control+z');
  await expect(tools.getByRole('button', { name: 'Redo' })).toBeEnabled();
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('undone.png') });
});

test('imports into a zoomed view land on none of the older objects, and the view follows one placed outside it', async ({ page }, info) => {
  test.setTimeout(90_000);
  await open(page);
  await page.getByRole('toolbar', { name: 'Tools' }).getByRole('button', { name: 'Pan' }).click();
  const canvas = page.getByRole('region', { name: 'Drawing' }).locator('canvas');
  await canvas.click();
  for (let i = 0; i < 6; i++) await canvas.press('+'); // about 95 × 55 mm of the bed in view: four imports fill it
  const boxes: Box[] = [];
  for (let i = 0; i < 7; i++) {
    // 40 × 20 pixels at 1000 a metre: 40 × 20 mm.
    const bmp = Buffer.from(bmpFile(40, 20, halfBlack(40), { x: 1000, y: 1000 }));
    await importer(page).setInputFiles({ name: `logo-${i}.bmp`, mimeType: 'image/bmp', buffer: bmp });
    await expect(selected(page)).toContainText(`logo-${i}.bmp`);
    const box = await boxOf(page);
    for (const [j, older] of boxes.entries()) expect(overlap(box, older), `import ${i} on import ${j}`).toBe(false);
    boxes.push(box);
    await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath(`import-${i}.png`) });
  }
  for (const b of boxes) expect(b.x >= 0 && b.y >= 0 && b.x + b.w <= 200 && b.y + b.h <= 200).toBe(true);
});

test('new text at the overview\'s zoom is not hidden under its handles', async ({ page }, info) => {
  await open(page);
  await page.getByRole('toolbar', { name: 'Tools' }).getByRole('button', { name: 'Text', exact: true }).click();
  const canvas = page.getByRole('region', { name: 'Drawing' }).locator('canvas');
  const area = (await canvas.boundingBox())!;
  await page.mouse.click(area.x + area.width * 0.4, area.y + area.height * 0.35);
  await page.keyboard.type('PCB 7');
  await page.keyboard.press('Enter'); // done typing: the text stays selected, with its handles
  const text = await boxOf(page);
  const a = await bedPoint(page, text.x, text.y), b = await bedPoint(page, text.x + text.w, text.y + text.h);
  expect(b.y - a.y).toBeLessThan(20); // 5 mm at the overview's zoom: small on the screen
  /** The canvas's pixels inside the text's box, inset past the selection's 2-pixel line. */
  const inside = () =>
    canvas.evaluate((c: HTMLCanvasElement, [x0, y0, x1, y1]) => {
      const dpr = window.devicePixelRatio || 1;
      const [sx, sy] = [Math.ceil(x0 * dpr) + 2, Math.ceil(y0 * dpr) + 2];
      return Array.from(c.getContext('2d')!.getImageData(sx, sy, Math.floor(x1 * dpr) - 2 - sx, Math.floor(y1 * dpr) - 2 - sy).data);
    }, [a.x, a.y, b.x, b.y]);
  await page.waitForTimeout(100); // a frame
  const withHandles = await inside();
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('text-selected.png') });
  await canvas.press('Escape'); // nothing selected: no handles
  await expect(selected(page)).toHaveCount(0);
  await page.waitForTimeout(100);
  const bare = await inside();
  expect(bare.some((v, i) => i % 4 === 0 && v < 200)).toBe(true); // the words are drawn there
  expect(withHandles).toEqual(bare); // and the handles cover none of them
  const at = (await canvas.boundingBox())!;
  await page.screenshot({ path: info.outputPath('text-unselected.png'), clip: { x: at.x + a.x - 20, y: at.y + a.y - 20, width: b.x - a.x + 40, height: b.y - a.y + 40 } });
});

test('the dry run of a warm head says the pause comes at stop 1, not stop 0', async ({ page }, info) => {
  test.setTimeout(150_000);
  await open(page, 1); // at 1x the head cools slowly enough to be asked about while still warm
  await drawFilledRectangle(page, [0.3, 0.3], [0.33, 0.33]);
  await page.getByLabel('Full dose').fill('8000'); // long stops: the first one alone warms the head past its limit
  // A first exposure warms the LEDs' drivers (T4) to their 50 °C soft limit: the printer pauses it to cool.
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'paused', { timeout: 120_000 });
  await page.getByRole('button', { name: 'Stop', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'aborted');
  // Asked again at once, the head is at its limit or just under it: the next job pauses during its first stop.
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const thermal = page.getByTestId('dry-run').locator('li', { hasText: /^thermal:/ });
  await expect(thermal).toContainText(/T4 would reach its 50 °C soft limit \d+:\d\d:\d\d in, at stop 1 of \d+/, { timeout: 30_000 });
  await expect(thermal).not.toContainText('stop 0 of');
  await page.getByRole('dialog').screenshot({ path: info.outputPath('dry-run-stop-1.png') });
});
