// Issue 41 item 6: normal KiCad output, an empty bottom paste and an NPTH.drl with no holes, is said as a
// quiet one-line note, not in red as a problem, and the canvas stays where it was; a copper layer that
// draws nothing stays a problem.
import { expect, test } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { IMPORT_LABEL, importBoard, openStudio, PCB, selected } from './boards';

const DEMO = ['demo-F_Cu.gbr', 'demo-B_Cu.gbr', 'demo-F_Mask.gbr', 'demo-Edge_Cuts.gbr', 'demo-PTH.drl'];

test('an empty paste layer and an empty NPTH.drl are a quiet note that does not move the canvas', async ({ page }, info) => {
  await openStudio(page);
  const canvas = page.getByTestId('editor-canvas');
  const before = (await canvas.boundingBox())!;
  await importBoard(page, '', [...DEMO, ['empty/demo-B_Paste.gbr', 'demo-B_Paste.gbr'], ['empty/demo-NPTH.drl', 'demo-NPTH.drl']]);
  await expect(selected(page)).toContainText('Board demo', { timeout: 20_000 });
  const note = page.getByRole('status', { name: 'Import notes' });
  await expect(note).toHaveText(/^Placed\. Empty, as is normal for their kind: demo-B_Paste\.gbr \(draws nothing\), demo-NPTH\.drl \(no holes\)\. OK$/);
  await expect(page.getByRole('status', { name: 'Import problems' })).toHaveCount(0);
  expect(await note.evaluate((e) => getComputedStyle(e).color)).not.toBe('rgb(179, 38, 30)'); // not the problems' red
  expect(await canvas.boundingBox()).toEqual(before);
  await page.screenshot({ path: info.outputPath('empty-layers-noted.png') });
  await note.getByRole('button', { name: 'OK' }).click();
  await expect(note).toHaveCount(0);
  expect(await canvas.boundingBox()).toEqual(before);
});

test('a copper layer that draws nothing stays a problem, with the normal empty layers said quietly beside it', async ({ page }, info) => {
  await openStudio(page);
  const emptyCopper = { name: 'demo-In1_Cu.gbr', mimeType: 'application/octet-stream', buffer: Buffer.from('%TF.FileFunction,Copper,L2,Inr*%\n%FSLAX46Y46*%\n%MOMM*%\nM02*\n') };
  await page.getByLabel(IMPORT_LABEL).setInputFiles([
    ...[...DEMO, 'empty/demo-NPTH.drl'].map((f) => ({ name: f.replace('empty/', ''), mimeType: 'application/octet-stream', buffer: readFileSync(join(PCB, f)) })),
    emptyCopper,
  ]);
  const problems = page.getByRole('status', { name: 'Import problems' });
  await expect(problems.getByRole('listitem')).toHaveText(['demo-In1_Cu.gbr: the Gerber file draws nothing'], { timeout: 20_000 });
  await expect(problems).toContainText('Empty, as is normal for its kind: demo-NPTH.drl (no holes).');
  expect(await problems.evaluate((e) => getComputedStyle(e).color)).toBe('rgb(179, 38, 30)');
  await page.screenshot({ path: info.outputPath('empty-copper-problem.png') });
});
