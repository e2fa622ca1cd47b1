// Issue 40: board sets as EasyEDA Pro, DipTrace and Eagle write them, a set whose heads contradict its names,
// numbered files and Gerber 2016 block apertures (hand-written in e2e/fixtures/pcb/cad-tools/, modelled on
// each tool's output), and a real Xpedition board from the corpus (app/src/pcb/corpus/), picked through the
// file picker. The panel shows the board's true size (from its outline,
// never from drawing layers), the layer exposed, the outline offered as a cutting guide, and what was guessed.
import { expect, test, type Page } from '@playwright/test';
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { PCB, exposeOf, importBoard, kindOf, openStudio, selected, sizeShown } from './boards';

const filesOf = (dir: string) => readdirSync(join(PCB, 'cad-tools', dir)).sort();
const problems = (page: Page) => page.getByRole('status', { name: 'Import problems' });

async function pick(page: Page, dir: string, name: string) {
  await importBoard(page, join('cad-tools', dir), filesOf(dir));
  await expect(selected(page)).toContainText(`Board ${name}`, { timeout: 20_000 });
}

/** Every file's layer and whether it is exposed, as the panel shows them. */
async function expectLayers(page: Page, layers: Record<string, [string, boolean]>) {
  for (const [file, [kind, exposed]] of Object.entries(layers)) {
    await expect(kindOf(page, file)).toHaveValue(kind);
    await expect(exposeOf(page, file)).toBeChecked({ checked: exposed });
  }
}

test('EasyEDA Pro and DipTrace boards come in at their outline’s size, whatever their drawing layers hold', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openStudio(page);

  await pick(page, 'easyeda-pro', 'Drill_PTH_Through.DRL');
  await expect(problems(page)).toHaveCount(0); // nothing lost, nothing guessed: each file says what it is
  expect(await sizeShown(page)).toEqual({ w: 33.4, h: 32 }); // not 237.5 × 76.3: the drill drawing is not the board
  await expectLayers(page, {
    'Gerber_TopLayer.GTL': ['copper-top', true],
    'Gerber_BoardOutlineLayer.GKO': ['outline', false],
    'Gerber_DrillDrawingLayer.GDD': ['other', false],
    'Gerber_DocumentLayer.GDL': ['other', false],
    'Drill_PTH_Through.DRL': ['drill', false],
  });
  await page.screenshot({ path: info.outputPath('easyeda-pro.png') });

  await pick(page, 'diptrace', 'BoardOutline.gbr');
  expect(await sizeShown(page)).toEqual({ w: 31.2, h: 48 }); // not 48.8 × 59.9: the dimension layer's measures lie outside
  await expectLayers(page, { 'Top.gbr': ['copper-top', true], 'BoardOutline.gbr': ['outline', false], 'Dimension.gbr': ['outline', false] });
  await selected(page).screenshot({ path: info.outputPath('diptrace-panel.png') });
});

test('an Eagle outline drawn with a zero-width aperture is the board’s edge and a cutting guide', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openStudio(page);
  await pick(page, 'eagle', 'blinky');
  expect(await sizeShown(page)).toEqual({ w: 38.1, h: 25.4 }); // 1.5 × 1 inch, corner to corner of the outline
  await expectLayers(page, { 'blinky.GTL': ['copper-top', true], 'blinky.GKO': ['outline', false], 'blinky.GTO': ['silk-top', false], 'blinky.TXT': ['drill', false] });
  // The outline is not refused: said of the silk only, whose hairline the studio widens.
  await expect(problems(page)).toContainText('blinky.GTO: 1 draw with a zero-width aperture, drawn 0.1 mm wide');
  await expect(problems(page)).not.toContainText('blinky.GKO');
  await problems(page).screenshot({ path: info.outputPath('eagle-problems.png') });
  await problems(page).getByRole('button', { name: 'OK' }).click();
  // Ticked, the outline is exposed with the copper: the cutting guide.
  await exposeOf(page, 'blinky.GKO').check();
  await expect(exposeOf(page, 'blinky.GKO')).toBeChecked();
  await page.screenshot({ path: info.outputPath('eagle-outline-guide.png') });
});

test('a file’s head beats its name; numbered files find their top copper and say how', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openStudio(page);

  // "top.grb" says "%LNtop silk*%": silk, not copper; layer1.grb says top copper.
  await pick(page, 'header-wins', 'bottom.grb');
  await expectLayers(page, { 'layer1.grb': ['copper-top', true], 'top.grb': ['silk-top', false], 'bottom.grb': ['mask-bottom', false] });
  await expect(problems(page)).toHaveCount(0);

  // f01 (the bottom copper) sorts first; f02 has the surface-mount pads, so it is the top.
  await pick(page, 'numbered', 'f0');
  await expectLayers(page, { 'f01.gbr': ['copper-bottom', false], 'f02.gbr': ['copper-top', true], 'f03.drl': ['drill', false] });
  await expect(problems(page)).toContainText('f02.gbr: taken for the top copper from what it draws: 8 pads without a hole, where surface-mount parts sit (against f01.gbr 0); check it');
  await expect(selected(page).getByRole('status').filter({ hasText: 'copper' })).toContainText('f02.gbr is taken for the top copper');
  await page.screenshot({ path: info.outputPath('numbered.png') });
});

test('a Gerber 2016 block aperture is drawn where it is flashed, with nothing to say', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openStudio(page);
  await pick(page, 'block-aperture', 'panel');
  await expectLayers(page, { 'panel-F_Cu.gbr': ['copper-top', true], 'panel-Edge_Cuts.gbr': ['outline', false] });
  await expect(problems(page)).toHaveCount(0); // no "tool 12 is not defined", no RangeError
  expect(await sizeShown(page)).toEqual({ w: 15, h: 15 });
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('block-aperture.png') });
});

test('a real Xpedition board (the corpus’s MinnowBoard Turbot): its pour’s quarter-arc cut-outs drawn whole, nothing said', async ({ page }, info) => {
  test.setTimeout(120_000);
  await openStudio(page);
  // The published files themselves (app/src/pcb/corpus/), not a fixture modelled on them.
  const dir = join('..', '..', '..', 'app', 'src', 'pcb', 'corpus', 'xpedition-minnowboard-turbot');
  const files = readdirSync(join(PCB, dir)).filter((f) => /\.(gdo|ncd)$/.test(f)).sort();
  await importBoard(page, dir, files);
  await expect(selected(page)).toContainText('Board 80101_0125_F200', { timeout: 30_000 });
  // No outline file: the board's edge is drawn in the copper, 0.005 in wide, and exposed with it: 99.187 × 73.787 mm,
  // shown to the panel's 0.1 mm.
  await expect.poll(() => sizeShown(page), { timeout: 30_000 }).toEqual({ w: 99.2, h: 73.8 });
  // 353 "skipping impossible arc" lines were said before, and the pour was cut at each.
  await expect(problems(page)).toHaveCount(0);
  await expectLayers(page, {
    '80101_0125_F200_L01_Top.gdo': ['copper-top', true],
    '80101_0125_F200_L12_Bottom.gdo': ['copper-bottom', false],
    '80101_0125_F200_SoldermaskTop.gdo': ['mask-top', false],
    '80101_0125_F200_ThruHolePlated.ncd': ['drill', false],
  });
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('xpedition-turbot.png') });
});
