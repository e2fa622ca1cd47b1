// The studio's grid editor in Chromium: draw, undo and redo, zoom and pan, and expose the drawing
// on the simulated printer.
import { expect, test } from '@playwright/test';
import { bedPoint, isDose, pixel } from './canvas';
import { bmpFile, halfBlack } from '../app/src/studio/image/picture-files.fixture';

test('draws a filled rectangle, undoes and redoes it, zooms, and exposes it', async ({ page }, info) => {
  test.setTimeout(90_000); // some 19,000 stops: the firmware's own C++ runs them, at 40x when the machine is not loaded
  await page.goto('/?simSpeed=40');
  await page.getByTestId('strategy').selectOption('serpentine'); // the stop-and-fire flow; the default (automatic) may scan
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
  // The dry run comes first, in the question before any LED fires: the machine without a fault, on
  // the bed, nothing cut by its edge, leveling (off since the link restarted the Mega), within the
  // printhead's cap and the thermal budget.
  const checks = page.getByTestId('dry-run').locator('li');
  await expect(checks).toHaveCount(6);
  for (const level of await checks.evaluateAll((li) => li.map((l) => l.getAttribute('data-level')))) expect(level).toBe('ok');
  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
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

test('imports a picture as an object: sized in mm, dithered, inverted, moved, resized and deleted', async ({ page }, info) => {
  await page.goto('/?simSpeed=40');
  await page.getByTestId('import-file').setInputFiles({ name: 'half.bmp', mimeType: 'image/bmp', buffer: Buffer.from(bmpFile(40, 20, halfBlack(40))) });
  // The file states no resolution: it is asked for, and gives the size.
  await page.getByLabel('Resolution').fill('25.4');
  await expect(page.getByTestId('import-dpi-size')).toHaveText('40.00 × 20.00 mm');
  await page.getByRole('button', { name: 'Place' }).click();
  const panel = page.getByTestId('object-panel');
  await expect(panel).toHaveAttribute('data-kind', 'image');
  await page.getByTestId('object-w').fill('60');
  await page.getByTestId('object-w').press('Enter');
  await expect(page.getByTestId('object-h')).toHaveValue('30'); // 40 × 20 pixels keep their proportions
  await expect(page.getByTestId('object-halftone')).toHaveValue('threshold'); // black and white: line art
  const field = async (name: string) => Number(await page.getByTestId(`object-${name}`).inputValue());
  const x = await field('x'), y = await field('y');
  const black = await bedPoint(page, x + 15, y + 15), white = await bedPoint(page, x + 45, y + 15);
  await expect.poll(() => pixel(page, black.x, black.y).then(isDose)).toBe(true);
  expect(isDose(await pixel(page, white.x, white.y))).toBe(false);
  await expect(page.getByTestId('expose-drawing')).toBeEnabled();
  await page.screenshot({ path: info.outputPath('imported.png'), fullPage: true });

  // Inverted, the white half is the one exposed; undo takes the inversion back, not the picture.
  await page.getByTestId('object-invert').check();
  await expect.poll(() => pixel(page, white.x, white.y).then(isDose)).toBe(true);
  expect(isDose(await pixel(page, black.x, black.y))).toBe(false);
  await page.getByTestId('undo').click();
  await expect.poll(() => pixel(page, black.x, black.y).then(isDose)).toBe(true);

  // Dragged by its middle with the select tool, it follows the pointer.
  const box = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.move(box.x + black.x, box.y + black.y);
  await page.mouse.down();
  await page.mouse.move(box.x + black.x + 20, box.y + black.y + 60, { steps: 6 });
  await page.mouse.up();
  await expect.poll(() => field('y')).toBeGreaterThan(y + 10);
  await expect.poll(() => pixel(page, black.x, black.y).then(isDose)).toBe(false);
  // Its south-east corner dragged outwards makes it larger, keeping its proportions.
  const se = await bedPoint(page, (await field('x')) + 60, (await field('y')) + 30);
  await page.mouse.move(box.x + se.x, box.y + se.y);
  await page.mouse.down();
  await page.mouse.move(box.x + se.x + 40, box.y + se.y + 40, { steps: 5 });
  await page.mouse.up();
  await expect.poll(() => field('w')).toBeGreaterThan(61);
  expect(await field('h')).toBeCloseTo((await field('w')) / 2, 0);
  await page.screenshot({ path: info.outputPath('moved-resized.png'), fullPage: true });

  await page.getByTestId('editor-canvas').press('Delete');
  await expect(panel).toBeHidden();
  await expect(page.getByTestId('expose-drawing')).toBeDisabled();
  await page.getByTestId('undo').click(); // the picture is back
  await expect(page.getByTestId('expose-drawing')).toBeEnabled();
});

test('text in a system font and a frame: placed, edited, planned with the drawing, merged into it', async ({ page }, info) => {
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const box = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.getByTestId('tool-text').click();
  await page.getByTestId('text-draft').fill('PCB 1');
  await page.getByTestId('text-height').fill('20');
  await page.getByTestId('text-font').fill('monospace');
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  await expect(page.getByTestId('object-panel')).toHaveAttribute('data-kind', 'text');
  await expect(page.getByTestId('object-h')).toHaveValue('20');
  const wide = Number(await page.getByTestId('object-w').inputValue());
  expect(wide).toBeGreaterThan(40); // five monospace glyphs at 20 mm
  await expect(page.getByTestId('expose-drawing')).toBeEnabled();
  // Longer words make a wider box at the same height.
  await page.getByTestId('object-text').fill('PCB 12');
  await page.getByTestId('object-text').blur();
  await expect.poll(async () => Number(await page.getByTestId('object-w').inputValue())).toBeGreaterThan(wide);
  // Some cells of the box are lit and some are not: glyphs, not a block.
  const lit = await page.getByTestId('editor-canvas').evaluate((c: HTMLCanvasElement) => {
    const d = c.getContext('2d')!.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i + 1] < d[i] - 15) n++;
    return n / (c.width * c.height);
  });
  expect(lit).toBeGreaterThan(0.001);
  expect(lit).toBeLessThan(0.1);
  // The job is the painting with the objects over it: the preview plans the text, stop by stop.
  await page.getByTestId('strategy').selectOption('serpentine');
  await page.getByTestId('view-preview').click();
  await expect(page.getByTestId('preview-summary')).toContainText(/^[1-9]\d* stops in/, { timeout: 20_000 });
  await page.getByTestId('view-draw').click();

  // A frame drawn around it is a guide: the job does not grow.
  await page.getByTestId('tool-frame').click();
  await page.mouse.move(box.x + box.width * 0.2, box.y + box.height * 0.2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.8, box.y + box.height * 0.8, { steps: 4 });
  await page.mouse.up();
  await expect(page.getByTestId('object-panel')).toHaveAttribute('data-kind', 'frame');
  await page.getByTestId('object-line').fill('3');
  await page.getByTestId('object-line').press('Enter');
  await expect(page.getByTestId('object-panel').locator('h2')).toHaveText('Frame (exposed)');
  await page.screenshot({ path: info.outputPath('text-and-frame.png'), fullPage: true });

  // Merged into the drawing, the text becomes cells the eraser can reach.
  await page.getByTestId('tool-select').click();
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  await expect(page.getByTestId('object-panel')).toHaveAttribute('data-kind', 'text');
  await page.getByTestId('object-merge').click();
  await expect(page.getByTestId('object-panel')).toBeHidden();
  await expect(page.getByTestId('expose-drawing')).toBeEnabled();
});

test('a file that is not a picture says so', async ({ page }) => {
  await page.goto('/?simSpeed=40');
  await page.getByTestId('import-file').setInputFiles({ name: 'notes.png', mimeType: 'image/png', buffer: Buffer.from('not a png at all') });
  await expect(page.getByTestId('import-error')).toContainText('not a picture');
});
