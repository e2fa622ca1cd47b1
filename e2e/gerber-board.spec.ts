// Issue 18, a board's Gerber and drill files in the studio: imported together as one object at the
// board's true size, each file's layer guessed and editable, the exposed layers chosen, drill dots,
// positive resist; the double-sided flip (the bottom copper mirrored about the board's left edge),
// a registration mark on both sides, one side a job (the bottom side made left out), the dry run
// stopping the bottom side, taken in, that lies off the bed, then "set the job origin here" with
// the head over the mark, and the exposure of that side on the simulated
// printer. The Gerber parser loads on demand through the stream stand-ins (app/src/pcb/*-shim.ts).
import { expect, test, type Page } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { bedPoint, isDose, pixel } from './canvas';

const DEMO = join(import.meta.dirname, 'fixtures/pcb');
const FILES = ['demo-B_Cu.gbr', 'demo-Edge_Cuts.gbr', 'demo-F_Cu.gbr', 'demo-F_Mask.gbr', 'demo-PTH.drl'];
/** The window: the outline's centre line, the 30 × 20 mm board (its 0.1 mm line's outer half lies outside). */
const WIN = { x0: 0, y1: 20 };

const panel = (page: Page) => page.getByRole('region', { name: 'Selected object' });
const layer = (page: Page, file: string) => page.locator(`[data-testid="board-layer"][data-file="${file}"]`);

async function placed(page: Page): Promise<{ x: number; y: number; w: number; h: number }> {
  const field = async (name: string) => Number(await page.getByTestId(`object-${name}`).inputValue());
  return { x: await field('x'), y: await field('y'), w: await field('w'), h: await field('h') };
}

/** Whether the bed's pixel over board mm (x, y), Y up, of an upright board placed at `box`, has a dose. */
async function dosedAt(page: Page, box: { x: number; y: number }, x: number, y: number): Promise<boolean> {
  const p = await bedPoint(page, box.x + x - WIN.x0, box.y + WIN.y1 - y);
  return isDose(await pixel(page, p.x, p.y));
}

async function zoomShot(page: Page, at: { x: number; y: number }, path: string) {
  const p = await bedPoint(page, at.x, at.y);
  const canvas = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.move(canvas.x + p.x, canvas.y + p.y);
  for (let i = 0; i < 5; i++) await page.mouse.wheel(0, -240);
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path });
  await page.getByTestId('editor-canvas').press('0'); // fit again
}

test('a two-sided board: layers chosen, drill dots, positive resist, the bottom flipped, a cut caught, the origin set at the head, exposed', async ({ page }, info) => {
  test.setTimeout(180_000);
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected', { timeout: 20_000 });

  // The five files picked together, and a stray one: one object, at the board's window, 30 × 20 mm; the stray file named.
  const stray = { name: 'demo-notes.gbr', mimeType: 'application/octet-stream', buffer: Buffer.from('ordered from the fab on Monday') };
  await page.getByLabel('Import artwork (SVG, PNG, JPG, BMP, GIF)').setInputFiles([...FILES.map((f) => ({ name: f, mimeType: 'application/octet-stream', buffer: readFileSync(join(DEMO, f)) })), stray]);
  await expect(panel(page)).toContainText('Board demo', { timeout: 20_000 });
  await expect(page.getByTestId('import-problems')).toContainText('demo-notes.gbr:');
  await page.getByTestId('import-problems').getByRole('button', { name: 'OK' }).click();
  await expect(page.getByTestId('import-problems')).toHaveCount(0);
  await expect(layer(page, 'demo-notes.gbr').getByTestId('board-layer-kind')).toHaveValue('other');
  let box = await placed(page);
  expect([box.w, box.h]).toEqual([30, 20]);
  const kinds = { 'demo-B_Cu.gbr': 'copper-bottom', 'demo-Edge_Cuts.gbr': 'outline', 'demo-F_Cu.gbr': 'copper-top', 'demo-F_Mask.gbr': 'mask-top', 'demo-PTH.drl': 'drill' };
  for (const [file, kind] of Object.entries(kinds)) {
    await expect(layer(page, file).getByTestId('board-layer-kind')).toHaveValue(kind);
    await expect(layer(page, file).getByTestId('board-layer-expose')).toBeChecked({ checked: kind === 'copper-top' });
  }
  await expect(page.getByTestId('board-drill')).toHaveValue('unexposed-dot');
  await expect(page.getByTestId('object-threshold')).toHaveValue('50'); // vector artwork: a coverage threshold, no halftone
  // The square pad at (5, 5) is exposed (dry film: copper is exposed); bare board is not.
  await expect.poll(() => dosedAt(page, box, 5.6, 5)).toBe(true);
  expect(await dosedAt(page, box, 27, 2)).toBe(false);

  // Layers chosen: the outline exposed as well; a file's kind changed and back.
  await layer(page, 'demo-Edge_Cuts.gbr').getByTestId('board-layer-expose').check();
  await layer(page, 'demo-F_Mask.gbr').getByTestId('board-layer-kind').selectOption('other');
  await expect(layer(page, 'demo-F_Mask.gbr').getByTestId('board-layer-kind')).toHaveValue('other');
  await layer(page, 'demo-F_Mask.gbr').getByTestId('board-layer-kind').selectOption('mask-top');
  await zoomShot(page, { x: box.x + 5, y: box.y + 15 }, info.outputPath('board-top-drill-dots.png'));
  await page.getByTestId('board-drill').selectOption('exposed-dot');
  await zoomShot(page, { x: box.x + 5, y: box.y + 15 }, info.outputPath('board-top-exposed-dots.png'));

  // Positive resist: the bare board is exposed, the copper is not.
  await page.getByLabel('Resist').selectOption('positive');
  await expect.poll(() => dosedAt(page, box, 27, 2)).toBe(true);
  expect(await dosedAt(page, box, 5.6, 5)).toBe(false);
  await page.getByLabel('Resist').selectOption('negative');

  // A registration mark 3 mm in from the lower left corner; the top side moved near the bed's left edge.
  await page.getByTestId('board-mark-add').click();
  await page.getByTestId('board-mark-x').fill('3');
  await page.getByTestId('board-mark-x').press('Enter');
  await page.getByTestId('board-mark-y').fill('3');
  await page.getByTestId('board-mark-y').press('Enter');
  await page.getByTestId('object-x').fill('10');
  await page.getByTestId('object-x').press('Enter');
  box = await placed(page);

  // The bottom side: turned over about the board's left edge, it lies mirrored left of the top side, off the bed.
  await page.getByTestId('board-flip-axis').selectOption('left-right');
  await page.getByTestId('board-flip-at').selectOption('start');
  await page.getByTestId('board-bottom').click();
  await expect(panel(page)).toContainText('Board demo (bottom)');
  await expect(panel(page).getByTestId('object-orientation')).toHaveText('mirrored');
  await expect(layer(page, 'demo-B_Cu.gbr').getByTestId('board-layer-expose')).toBeChecked();
  await expect(layer(page, 'demo-F_Cu.gbr').getByTestId('board-layer-expose')).not.toBeChecked();
  await expect(page.getByTestId('board-mark-x')).toHaveValue('3'); // the mark is the board's, on both sides
  const bottom = await placed(page);
  expect(bottom.x).toBeCloseTo(box.x - 30, 1);
  await expect(panel(page).getByTestId('object-off-bed')).toContainText('past the left edge');
  await expect(panel(page).getByTestId('object-off-bed')).toContainText('This side is left out of the job: that stops nothing');
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('board-both-sides.png') });

  // Made left out of the job (the top side is exposed first, the board turned over after): it stops nothing, and the dry run says which side.
  await expect(panel(page).getByLabel(/^Side exposed in this job/).locator('option:checked')).toHaveText('top side (demo)');
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  const clipping = dialog.getByRole('listitem').filter({ hasText: /^clipping:/ });
  await expect(clipping).toHaveAttribute('data-level', 'ok', { timeout: 30_000 });
  await expect(dialog.getByRole('listitem').filter({ hasText: /^sides:/ })).toContainText('the top side of board demo');
  await dialog.getByRole('button', { name: 'Cancel' }).click();

  // The bottom side taken into the job: the dry run names it as cut and stops the job.
  await panel(page).getByLabel(/^Side exposed in this job/).selectOption({ label: 'bottom side (demo (bottom))' });
  await expect(panel(page).getByTestId('object-off-bed')).toContainText('the dry run stops the job until that is accepted');
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await expect(clipping).toHaveAttribute('data-level', 'error', { timeout: 30_000 });
  await expect(clipping).toContainText('board demo (bottom)');
  await dialog.screenshot({ path: info.outputPath('board-dry-run-cut.png') });
  await dialog.getByRole('button', { name: 'Close' }).click();

  // The head jogged over the drilled mark (here: sent to 60, 70 mm), the job origin set there.
  await page.getByTestId('tab-position').click();
  await page.getByTestId('home').click();
  await page.getByTestId('goto-x').fill('60');
  await page.getByTestId('goto-y').fill('70');
  await page.getByTestId('goto').click();
  await expect(page.getByTestId('board-head')).toHaveText('head at X 60.00 Y 70.00 mm', { timeout: 30_000 });
  await page.getByTestId('board-origin').click();
  const there = await placed(page);
  // Mirrored, the mark 3 mm in from the lower left lies 3 mm in from the box's lower right.
  expect(Math.abs(there.x + there.w - 3 - 60)).toBeLessThanOrEqual(0.05);
  expect(Math.abs(there.y + there.h - 3 - 70)).toBeLessThanOrEqual(0.05);
  await expect(panel(page).getByTestId('object-off-bed')).toHaveCount(0);

  // The bottom side on the bed: the dry run passes and the job, that side alone, runs on the simulated printer.
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await expect(clipping).toHaveAttribute('data-level', 'ok', { timeout: 30_000 });
  await expect(dialog.getByRole('listitem').filter({ hasText: /^sides:/ })).toContainText('the bottom side of board demo');
  await dialog.screenshot({ path: info.outputPath('board-dry-run-ok.png') });
  await dialog.getByRole('button', { name: /^Expose/ }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 150_000 });
  await page.screenshot({ path: info.outputPath('board-exposed.png'), fullPage: true });
});
