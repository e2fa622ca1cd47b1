// Issue 18, "PCB artwork in, at its true size": pictures land at the resolution their headers
// state and an SVG at its units; a file that states none asks; objects turn and mirror; the
// resist polarity flips what is exposed; an object cut by the bed's edge stops the dry run until
// the cut is accepted; and the dose can be set in mJ/cm² once the LEDs' irradiance is measured.
import { expect, test, type Page } from '@playwright/test';
import { bedPoint, isDose, pixel } from './canvas';
import { bmpFile, halfBlack, jpegFile, pngFile } from '../app/src/studio/image/picture-files.fixture';
import { drawFilledRectangle } from './draw';

const PITCH_MM = 0.05;
const PPM_600 = 23622, PPM_300 = 11811;

async function open(page: Page) {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected', { timeout: 20_000 });
}

async function importFile(page: Page, name: string, mimeType: string, bytes: Uint8Array | string) {
  await page.getByLabel('Import artwork (SVG, PNG, JPG, BMP, GIF)').setInputFiles({ name, mimeType, buffer: Buffer.from(bytes) });
}

const panel = (page: Page) => page.getByRole('region', { name: 'Selected object' });

/** The selected object's place and size, mm, as its panel shows them. */
async function placed(page: Page): Promise<{ x: number; y: number; w: number; h: number }> {
  const field = async (name: string) => Number(await page.getByTestId(`object-${name}`).inputValue());
  return { x: await field('x'), y: await field('y'), w: await field('w'), h: await field('h') };
}

test('pictures land at the size their resolution states, within half a cell; one that states none asks', async ({ page }, info) => {
  test.setTimeout(120_000);
  await open(page);
  // A 30 × 20 mm board at 600 dpi lands 30 × 20 mm, not 40 mm wide; and the others as stated.
  const files: [string, string, Uint8Array, { x: number; y: number }, number][] = [
    ['board-600dpi.png', 'image/png', pngFile(709, 472, halfBlack(709), { pixelsPerMetre: { x: PPM_600, y: PPM_600 } }), { x: (709 / PPM_600) * 1000, y: (472 / PPM_600) * 1000 }, 600],
    ['board-300dpi.jpg', 'image/jpeg', jpegFile(354, 236, halfBlack(354), { jfif: { units: 1, x: 300, y: 300 } }), { x: (354 / 300) * 25.4, y: (236 / 300) * 25.4 }, 300],
    ['board-exif.jpg', 'image/jpeg', jpegFile(472, 240, halfBlack(472), { jfif: { units: 0, x: 1, y: 1 }, exif: { unit: 2, x: [600, 1], y: [600, 1] } }), { x: (472 / 600) * 25.4, y: (240 / 600) * 25.4 }, 600],
    ['board-300dpi.bmp', 'image/bmp', bmpFile(354, 236, halfBlack(354), { x: PPM_300, y: PPM_300 }), { x: (354 / PPM_300) * 1000, y: (236 / PPM_300) * 1000 }, 300],
  ];
  for (const [name, mime, bytes, trueMm, dpi] of files) {
    await importFile(page, name, mime, bytes);
    await expect(panel(page)).toContainText(`Picture ${name}`, { timeout: 15_000 });
    const box = await placed(page);
    expect(Math.abs(box.w - trueMm.x), `${name} width`).toBeLessThanOrEqual(PITCH_MM / 2);
    expect(Math.abs(box.h - trueMm.y), `${name} height`).toBeLessThanOrEqual(PITCH_MM / 2);
    // Black and white: a threshold by coverage, at half a cell.
    await expect(page.getByTestId('object-halftone')).toHaveValue('threshold');
    await expect(page.getByTestId('object-threshold')).toHaveValue('50');
    // The resolution it is shown at: its pixels over its width in whole cells, within 1 %.
    expect(Math.abs(Number(await page.getByTestId('object-dpi').inputValue()) / dpi - 1)).toBeLessThan(0.01);
  }
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('true-size-imports.png') });

  // No resolution in the file: it is asked for, prefilled with the last one used (none yet: 600).
  await importFile(page, 'plain.png', 'image/png', pngFile(300, 150, halfBlack(300)));
  const ask = page.getByRole('form', { name: 'Size of plain.png' });
  await expect(ask).toContainText('its header gives no resolution');
  await expect(ask.getByLabel('Resolution')).toHaveValue('600');
  await ask.getByLabel('Resolution').fill('300');
  await expect(ask).toContainText('25.40 × 12.70 mm');
  await ask.getByRole('button', { name: 'Place' }).click();
  await expect(panel(page)).toContainText('Picture plain.png');
  expect(await placed(page)).toMatchObject({ w: 25.4, h: 12.7 });
  await importFile(page, 'plain-2.png', 'image/png', pngFile(300, 150, halfBlack(300)));
  await expect(page.getByRole('form', { name: 'Size of plain-2.png' }).getByLabel('Resolution')).toHaveValue('300');
  await page.getByRole('form', { name: 'Size of plain-2.png' }).getByRole('button', { name: 'Cancel' }).click();
  await expect(page.getByRole('form', { name: 'Size of plain-2.png' })).toBeHidden();
});

test('an SVG and a tagged PNG: turned, mirrored, positive resist, a cut object accepted and exposed', async ({ page }, info) => {
  test.setTimeout(120_000);
  await open(page);
  // An L, 16 × 10 mm: a 4 mm bar down the left, a 2 mm bar along the bottom.
  const svg = '<svg xmlns="http://www.w3.org/2000/svg" width="16mm" height="10mm" viewBox="0 0 160 100"><path d="M0 0H40V80H160V100H0Z"/></svg>';
  await importFile(page, 'board.svg', 'image/svg+xml', svg);
  await expect(panel(page)).toContainText('SVG board.svg', { timeout: 15_000 });
  let box = await placed(page);
  expect([box.w, box.h]).toEqual([16, 10]);
  await expect(page.getByTestId('object-halftone')).toHaveValue('threshold');
  const canvasPoint = (mmX: number, mmY: number) => bedPoint(page, box.x + mmX, box.y + mmY);
  const bar = await canvasPoint(2, 4), blank = await canvasPoint(10, 4);
  await expect.poll(async () => isDose(await pixel(page, bar.x, bar.y))).toBe(true);
  expect(isDose(await pixel(page, blank.x, blank.y))).toBe(false);

  // A quarter turn clockwise about its middle: 10 × 16 mm, the left bar now along the top.
  await panel(page).getByRole('button', { name: 'Turn right' }).click();
  await expect(panel(page).getByTestId('object-orientation')).toHaveText('turned 90°');
  box = await placed(page);
  expect([box.w, box.h]).toEqual([10, 16]);
  const top = await canvasPoint(5, 2), middle = await canvasPoint(6, 10);
  await expect.poll(async () => isDose(await pixel(page, top.x, top.y))).toBe(true);
  expect(isDose(await pixel(page, middle.x, middle.y))).toBe(false);
  // Mirrored left to right as it lies: the bottom bar, now down the left, goes to the right.
  await panel(page).getByRole('button', { name: 'Mirror X' }).click();
  await expect(panel(page).getByTestId('object-orientation')).toHaveText('mirrored, turned 270°');
  const right = await canvasPoint(9, 10), left = await canvasPoint(1, 10);
  await expect.poll(async () => isDose(await pixel(page, right.x, right.y))).toBe(true);
  expect(isDose(await pixel(page, left.x, left.y))).toBe(false);
  const canvas = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.move(canvas.x + middle.x, canvas.y + middle.y);
  for (let i = 0; i < 6; i++) await page.mouse.wheel(0, -240);
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('svg-turned-mirrored.png') });
  await page.getByTestId('editor-canvas').press('0'); // fit again
  await expect.poll(async () => isDose(await pixel(page, right.x, right.y))).toBe(true);

  // Positive resist: what the artwork does not cover is exposed, the bar is not.
  await page.getByLabel('Resist').selectOption('positive');
  await expect.poll(async () => isDose(await pixel(page, middle.x, middle.y))).toBe(true);
  expect(isDose(await pixel(page, right.x, right.y))).toBe(false);

  // A 600 dpi PNG, 80 pixels square (3.4 mm), moved over the bed's right edge: cut, and shown so.
  await importFile(page, 'tagged.png', 'image/png', pngFile(80, 80, halfBlack(80), { pixelsPerMetre: { x: PPM_600, y: PPM_600 } }));
  await expect(panel(page)).toContainText('Picture tagged.png');
  expect((await placed(page)).w).toBe(3.4);
  await expect(panel(page).getByRole('status')).toHaveCount(0);
  await page.getByTestId('object-x').fill('198');
  await page.getByTestId('object-x').press('Enter');
  await expect(panel(page).getByRole('status')).toContainText('Off the bed: 1.4 mm past the right edge.');
  const edge = await bedPoint(page, 200, (await placed(page)).y + 1.7);
  const at = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.move(at.x + edge.x, at.y + edge.y);
  for (let i = 0; i < 8; i++) await page.mouse.wheel(0, -240);
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('cut-object.png') });
  await page.getByTestId('editor-canvas').press('0');

  // The dry run names it and stops the job; accepted, the job runs with what lies on the bed.
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  const clipping = dialog.getByRole('listitem').filter({ hasText: /^clipping:/ });
  await expect(clipping).toHaveAttribute('data-level', 'error');
  await expect(clipping).toContainText(/picture tagged\.png: 1\.4 mm past the right edge; \d+ % of its exposed cells are off the bed/);
  await expect(dialog.getByRole('listitem').filter({ hasText: /^envelope:/ })).toHaveAttribute('data-level', 'ok');
  await expect(dialog).toContainText('Not exposed: fix what is marked above.');
  await expect(dialog.getByRole('button', { name: /Expose/ })).toHaveCount(0);
  await dialog.screenshot({ path: info.outputPath('dry-run-cut.png') });
  await dialog.getByRole('checkbox', { name: 'Accept the cut: expose only what lies on the bed' }).check();
  await expect(clipping).toHaveAttribute('data-level', 'warning');
  await expect(clipping).toContainText('cut, accepted: picture tagged.png');
  await dialog.screenshot({ path: info.outputPath('dry-run-accepted.png') });
  await dialog.getByRole('button', { name: 'Expose anyway' }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 90_000 });
  await page.screenshot({ path: info.outputPath('exposed.png'), fullPage: true });
});

test('the dose in mJ/cm²: ms only until the LEDs\' irradiance is measured, then through it, ms beside', async ({ page }, info) => {
  test.setTimeout(90_000);
  await open(page);
  // The simulated printer reports the firmware's default irradiance: no measurement.
  await expect(page.getByTestId('dose-calibration')).toContainText('the firmware\'s default, not a measurement');
  await expect(page.getByRole('combobox', { name: 'Dose unit' }).getByRole('option', { name: 'mJ/cm²' })).toBeDisabled();

  await page.getByRole('tab', { name: 'Settings' }).click();
  for (const [led, value] of ['2000000', '1950000', '2000000', '1900000'].entries()) await page.getByLabel(`LED ${led} irradiance`).fill(value);
  await page.getByRole('button', { name: 'Apply', exact: true }).click();
  await expect(page.getByTestId('dose-calibration')).toBeHidden();

  await page.getByRole('combobox', { name: 'Dose unit' }).selectOption('mJ/cm²');
  await expect(page.getByLabel('Full dose')).toHaveValue('8'); // the 4 ms set, at LED 0's 2 W/cm²
  await expect(page.getByTestId('full-mj-ms')).toHaveText('= 4.00–4.21 ms a cell');
  await page.getByLabel('Full dose').fill('10');
  await page.getByLabel('Full dose').press('Enter');
  await expect(page.getByTestId('full-mj-ms')).toHaveText('= 5.00–5.26 ms a cell');
  await page.screenshot({ path: info.outputPath('dose-in-mj.png'), fullPage: true });

  await drawFilledRectangle(page, [0.4, 0.4], [0.42, 0.42]);
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  await expect(dialog).toContainText(/at a full dose of 10 mJ\/cm²\./);
  await expect(dialog.getByText(/^dose: the longest exposure is 5\.3 ms$/)).toBeVisible(); // LED 3's 1.9 W/cm²
  await dialog.getByRole('button', { name: 'Expose now' }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 60_000 });

  // The material test in mJ/cm² too.
  await page.getByRole('button', { name: 'Material test…' }).click();
  await page.getByTestId('material-unit').selectOption('mJ/cm²');
  await expect(page.getByTestId('material-times')).toContainText(/mJ\/cm², [\d.]+ mJ\/cm²$/);
});
