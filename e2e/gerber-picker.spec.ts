// Issue 29 item 8: the import's file picker hid common Gerber and drill extensions, so a person had to
// switch the dialog to "All files". The picker now offers them; files of those extensions picked there
// come in as one board.
import { expect, test } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { IMPORT_LABEL, kindOf, openStudio, PCB, selected } from './boards';

/** What testers found hidden, each as a board's file: the same copper, mask, drill and drawing under those names. */
const HIDDEN: [string, string][] = [
  ['demo.gbx', 'demo-F_Cu.gbr'],
  ['demo.grb', 'demo-F_Cu.gbr'],
  ['demo.top', 'demo-F_Cu.gbr'],
  ['demo.bot', 'demo-B_Cu.gbr'],
  ['demo.gto', 'demo-F_Mask.gbr'],
  ['demo.gbo', 'demo-F_Mask.gbr'],
  ['demo.gtp', 'demo-F_Mask.gbr'],
  ['demo.gbp', 'demo-F_Mask.gbr'],
  ['demo.gdo', 'demo-Edge_Cuts.gbr'],
  ['demo.cnc', 'demo-PTH.drl'],
  ['demo.tap', 'demo-PTH.drl'],
  ['demo.ncd', 'demo-PTH.drl'],
];

test('the file picker offers Gerber and drill extensions, and files picked there come in as one board', async ({ page }, info) => {
  test.setTimeout(90_000);
  await openStudio(page);

  // The picker a person opens by clicking the import control: what it offers without "All files".
  const chooser = page.waitForEvent('filechooser');
  await page.getByLabel(IMPORT_LABEL).click();
  const dialog = await chooser;
  expect(dialog.isMultiple()).toBe(true);
  const offered = (await dialog.element().getAttribute('accept'))!.split(',');
  for (const ext of ['gbx', 'grb', 'cnc', 'top', 'bot', 'tap', 'gdo', 'ncd', 'gto', 'gbo', 'gtp', 'gbp', 'gbr', 'gtl', 'gbl', 'drl', 'xln', 'exc', 'cmp', 'sol', 'art', 'pho'])
    expect(offered, `.${ext} offered`).toContain(`.${ext}`);
  expect(offered).toContain('image/png'); // pictures still

  // Picked there: one board of twelve files, the OrCAD .top/.bot read as copper and the drill files as drill.
  await dialog.setFiles(HIDDEN.map(([name, from]) => ({ name, mimeType: 'application/octet-stream', buffer: readFileSync(join(PCB, from)) })));
  await expect(selected(page)).toContainText('Board demo', { timeout: 20_000 });
  await expect(selected(page).getByRole('row')).toHaveCount(HIDDEN.length + 1); // a heading row and one a file
  await expect(kindOf(page, 'demo.top')).toHaveValue('copper-top');
  await expect(kindOf(page, 'demo.bot')).toHaveValue('copper-bottom');
  for (const drill of ['demo.cnc', 'demo.tap', 'demo.ncd']) await expect(kindOf(page, drill)).toHaveValue('drill');
  await expect(page.getByRole('status', { name: 'Import problems' })).toHaveCount(0);
  await page.screenshot({ path: info.outputPath('picked-hidden-extensions.png'), fullPage: true });
});
