// Issue 29 item 9: Veribest's .ncd drill file put a hole at the origin (its zero set, G93X000000Y000000,
// read as a hole), so the board came out larger than its copper; and the import's problems were a
// run-together wall of red text. The board is now its copper's size, and the problems are one entry a file.
// Issue 40: the copper's circles, four quarter arcs each with no quadrant mode set, were "impossible arcs"
// to the plotter (single-quadrant.ts): they are drawn, as gerbv draws them, and nothing is left to say.
import { expect, test } from '@playwright/test';
import { exposeOf, importBoard, kindOf, openStudio, selected, sizeShown } from './boards';
import { bedPoint } from './canvas';

/**
 * The copper's extent, 2.19 to 41.47 mm by 2.19 to 23.69 mm (boardWindow in app/src/pcb/board-artwork.ts prints
 * it): with no outline, the board is what may be exposed. The assembly drawing's frame (1.705 × 1.005 in) is a
 * drawing, never exposed, and since issue 40 it no longer sets the size.
 */
const BOARD_MM = { w: 41.4655 - 2.19456, h: 23.6855 - 2.19456 };

test('a Veribest board: the drill file adds no hole at the origin, so the board is its copper’s size; its quarter-arc circles drawn with nothing to say', async ({ page }, info) => {
  test.setTimeout(90_000);
  await openStudio(page);

  await importBoard(page, 'veribest', ['AssemblyTop.gdo', 'EtchLayer2Bottom.gdo', 'ThruHolePlated.ncd']);
  await expect(selected(page)).toContainText('Board ', { timeout: 20_000 });
  // Its three circles were "skipping impossible arc (lines 35, 41, 47)": now drawn, and no problem is said.
  await expect(page.getByRole('status', { name: 'Import problems' })).toHaveCount(0);

  // 39.3 × 21.5 mm: with a hole at the origin it was 45.5 × 27.7, and with the assembly drawing 43.3 × 25.5.
  const size = await sizeShown(page);
  expect(Math.abs(size.w - BOARD_MM.w), `width ${size.w} mm`).toBeLessThanOrEqual(0.1);
  expect(Math.abs(size.h - BOARD_MM.h), `height ${size.h} mm`).toBeLessThanOrEqual(0.1);
  await expect(kindOf(page, 'EtchLayer2Bottom.gdo')).toHaveValue('copper-bottom');
  await expect(kindOf(page, 'AssemblyTop.gdo')).toHaveValue('other'); // a drawing, though its name says "Top"
  await expect(kindOf(page, 'ThruHolePlated.ncd')).toHaveValue('drill');
  await expect(exposeOf(page, 'EtchLayer2Bottom.gdo')).toBeChecked();

  // The holes on their pads: a dot left unexposed at each, seen close up.
  const x = Number(await selected(page).getByRole('spinbutton', { name: /^X\b/ }).inputValue());
  const y = Number(await selected(page).getByRole('spinbutton', { name: /^Y\b/ }).inputValue());
  const p = await bedPoint(page, x + size.w / 2, y + size.h / 2);
  const canvas = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.move(canvas.x + p.x, canvas.y + p.y);
  for (let i = 0; i < 6; i++) await page.mouse.wheel(0, -240);
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('veribest-holes-on-pads.png') });
});

test('a board none of whose files draws: one entry a file says why, readable', async ({ page }, info) => {
  await openStudio(page);
  await page.getByLabel(/^Import artwork/).setInputFiles([
    { name: 'notes.gbr', mimeType: 'application/octet-stream', buffer: Buffer.from('ordered from the fab on Monday') },
    { name: 'empty.gdo', mimeType: 'application/octet-stream', buffer: Buffer.from('') },
    { name: 'holes.ncd', mimeType: 'application/octet-stream', buffer: Buffer.from('M48\nMETRIC\nT1C0.8\n%\nT1\nM30\n') },
  ]);
  const error = page.getByRole('alert').filter({ hasText: 'Nothing to place' });
  await expect(error).toBeVisible({ timeout: 20_000 });
  await expect(error.getByRole('listitem')).toHaveText([
    /^notes\.gbr: not a Gerber or Excellon drill file/,
    'empty.gdo: the file is empty',
    'holes.ncd: the drill file has no holes',
  ]);
  await error.screenshot({ path: info.outputPath('import-refused-one-per-file.png') });
  await error.getByRole('button', { name: 'OK' }).click();
  await expect(error).toHaveCount(0);
});
