// Issue 29 item 7: boards from gEDA, Eagle and Mentor arrived with no layer exposed, an empty box, and
// "Expose drawing" said nothing was drawn. Layers are now guessed from what the files say (X2 attributes,
// the names and comments each CAD tool writes) and draw (copper's pads and tracks); with no copper found,
// the board says so and exposes its first layer.
import { expect, test } from '@playwright/test';
import { exposeOf, importBoard, kindOf, openStudio, selected } from './boards';

test('gEDA, Eagle, X2 and Mentor boards arrive with their copper exposed; a board with none says so and exposes its first layer', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openStudio(page);

  // gEDA PCB names its layers by side ("front", "back", "frontmask"), its drawing "fab".
  await importBoard(page, 'geda', ['blinky.front.gbr', 'blinky.back.gbr', 'blinky.frontmask.gbr', 'blinky.fab.gbr', 'blinky.plated-drill.cnc']);
  await expect(selected(page)).toContainText('Board blinky', { timeout: 20_000 });
  const geda = { 'blinky.front.gbr': 'copper-top', 'blinky.back.gbr': 'copper-bottom', 'blinky.frontmask.gbr': 'mask-top', 'blinky.fab.gbr': 'other', 'blinky.plated-drill.cnc': 'drill' };
  for (const [file, kind] of Object.entries(geda)) {
    await expect(kindOf(page, file)).toHaveValue(kind);
    await expect(exposeOf(page, file)).toBeChecked({ checked: kind === 'copper-top' });
  }
  await expect(selected(page).getByRole('status').filter({ hasText: 'copper' })).toHaveCount(0); // nothing to say: the files said it
  await expect(page.getByRole('button', { name: 'Expose drawing' })).toBeEnabled();
  await selected(page).screenshot({ path: info.outputPath('geda-board-panel.png') });

  // Eagle's "top-cop.gbx": the name's words.
  await importBoard(page, 'eagle', ['top-cop.gbx']);
  await expect(selected(page)).toContainText('Board top-cop.gbx', { timeout: 20_000 });
  await expect(kindOf(page, 'top-cop.gbx')).toHaveValue('copper-top');
  await expect(exposeOf(page, 'top-cop.gbx')).toBeChecked();

  // A name that says nothing, an X2 attribute that says bottom copper.
  await importBoard(page, 'x2', ['layer2.gbr']);
  await expect(selected(page)).toContainText('Board layer2.gbr', { timeout: 20_000 });
  await expect(kindOf(page, 'layer2.gbr')).toHaveValue('copper-bottom');
  await expect(exposeOf(page, 'layer2.gbr')).toBeChecked();

});

test('Mentor boards that say nothing: copper taken from what a file draws, or, with none, the board says so and exposes its first layer', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openStudio(page);
  // A file that draws no copper and says nothing: the board says no copper was found, and exposes its first layer.
  await importBoard(page, 'mentor', ['artwork_2.grb']);
  await expect(selected(page)).toContainText('Board artwork_2.grb', { timeout: 20_000 });
  const none = selected(page).getByRole('status').filter({ hasText: 'copper' });
  await expect(none).toContainText('No copper layer found.');
  await expect(none).toContainText('Exposed: artwork_2.grb.');
  await expect(kindOf(page, 'artwork_2.grb')).toHaveValue('other');
  await expect(exposeOf(page, 'artwork_2.grb')).toBeChecked();
  await selected(page).screenshot({ path: info.outputPath('no-copper-notice.png') });
  // Something is drawn: "Expose drawing" opens its dry run rather than saying nothing is drawn.
  const expose = page.getByRole('button', { name: 'Expose drawing' });
  await expect(expose).toBeEnabled();
  await expose.click();
  const dialog = page.getByRole('dialog', { name: 'Expose the drawing?' });
  await expect(dialog).toBeVisible();
  await dialog.screenshot({ path: info.outputPath('no-copper-dry-run.png') });
  await dialog.getByRole('button', { name: 'Cancel' }).click();
  // Unticked, the board says nothing is exposed.
  await exposeOf(page, 'artwork_2.grb').uncheck();
  await expect(none).toContainText('Nothing is exposed.');

  // Mentor's "artwork_1.grb" says nothing at all: it draws pads and tracks, so it is taken for the top copper, and the board says why.
  await importBoard(page, 'mentor', ['artwork_1.grb']);
  await expect(selected(page)).toContainText('Board artwork_1.grb', { timeout: 20_000 });
  await expect(kindOf(page, 'artwork_1.grb')).toHaveValue('copper-top');
  await expect(exposeOf(page, 'artwork_1.grb')).toBeChecked();
  const guessed = selected(page).getByRole('status').filter({ hasText: 'copper' });
  await expect(guessed).toContainText('No file says it is copper: artwork_1.grb is taken for the top copper, as it draws pads and tracks as copper does.');
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('mentor-copper-from-content.png') });
  // The user settles it: the board stops saying it.
  await kindOf(page, 'artwork_1.grb').selectOption('copper-bottom');
  await expect(guessed).toHaveCount(0);
});
