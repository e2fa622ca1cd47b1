// Issue 29 item 14 (part): a Gerber board's panel showed halftone, contrast and gamma, which mean nothing to
// vector artwork; and after the first import the Import control fell below the fold at 1440 × 900 and
// 1280 × 720. A board's panel now shows only its coverage threshold and invert, and the Import control stays
// in view without scrolling.
import { expect, test } from '@playwright/test';
import { IMPORT_LABEL, importBoard, openStudio, selected } from './boards';
import { pngFile, halfBlack } from '../app/src/studio/image/picture-files.fixture';

const DEMO = ['demo-B_Cu.gbr', 'demo-Edge_Cuts.gbr', 'demo-F_Cu.gbr', 'demo-F_Mask.gbr', 'demo-PTH.drl'];

test('a board’s panel has no halftone, contrast or gamma; a picture’s still has them', async ({ page }, info) => {
  await openStudio(page);
  await importBoard(page, '.', DEMO);
  await expect(selected(page)).toContainText('Board demo', { timeout: 20_000 });
  for (const name of ['Halftone', 'Contrast', 'Gamma']) await expect(selected(page).getByLabel(name)).toHaveCount(0);
  await expect(selected(page).getByRole('spinbutton', { name: /^Threshold/ })).toHaveValue('50');
  await expect(selected(page).getByRole('checkbox', { name: 'Invert' })).toBeVisible();
  await selected(page).screenshot({ path: info.outputPath('board-panel-no-halftone.png') });

  await page.getByLabel(IMPORT_LABEL).setInputFiles({ name: 'logo.png', mimeType: 'image/png', buffer: Buffer.from(pngFile(60, 40, halfBlack(60), { pixelsPerMetre: { x: 23622, y: 23622 } })) });
  await expect(selected(page)).toContainText('Picture logo.png', { timeout: 15_000 });
  for (const name of ['Halftone', 'Contrast', 'Gamma']) await expect(selected(page).getByLabel(name)).toBeVisible();
});

for (const size of [{ width: 1440, height: 900 }, { width: 1280, height: 720 }]) {
  test(`at ${size.width} × ${size.height} the Import control stays in view after a board is imported`, async ({ page }, info) => {
    await openStudio(page, size);
    const importControl = page.getByLabel(IMPORT_LABEL);
    await expect(importControl).toBeInViewport();
    await importBoard(page, '.', DEMO);
    await expect(selected(page)).toContainText('Board demo', { timeout: 20_000 });
    await expect(importControl).toBeInViewport();
    expect(await page.evaluate(() => window.scrollY)).toBe(0);
    await page.screenshot({ path: info.outputPath(`after-import-${size.width}x${size.height}.png`) });
    // A second import from there, without scrolling.
    await importBoard(page, 'eagle', ['top-cop.gbx']);
    await expect(selected(page)).toContainText('Board top-cop.gbx', { timeout: 20_000 });
    await expect(importControl).toBeInViewport();
  });
}
