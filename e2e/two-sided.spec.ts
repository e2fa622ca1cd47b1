// Issue 29 item 10, a two-sided board exposed one side a job: "Make bottom side" leaves the new side
// out (drawn by its outline), the board's panel says which side the job exposes and changes it, and the
// job's question says it. A project from before, with both sides in the job, is stopped by the dry run,
// which says so and offers to leave one side out.
import { expect, test, type Page } from '@playwright/test';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

const DEMO = join(import.meta.dirname, 'fixtures/pcb');
const FILES = ['demo-B_Cu.gbr', 'demo-Edge_Cuts.gbr', 'demo-F_Cu.gbr', 'demo-PTH.drl'];

const panel = (page: Page) => page.getByRole('region', { name: 'Selected object' });
const sideChoice = (page: Page) => panel(page).getByLabel(/^Side exposed in this job/);
const question = (page: Page) => page.getByRole('dialog', { name: 'Expose the drawing?' });
const sidesLine = (page: Page) => question(page).getByRole('listitem').filter({ hasText: /^sides:/ });

async function ask(page: Page) {
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await expect(question(page).getByRole('listitem').first()).toBeVisible({ timeout: 30_000 });
}

test('a two-sided board: one side a job, said and chosen; both sides of an older project stopped, one left out from the question', async ({ page }, info) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByText('Connected to the simulated printer.')).toBeVisible({ timeout: 20_000 });
  await page.getByLabel('Import artwork (SVG, PNG, JPG, BMP, GIF)').setInputFiles(FILES.map((f) => ({ name: f, mimeType: 'application/octet-stream', buffer: readFileSync(join(DEMO, f)) })));
  await expect(panel(page)).toContainText('Board demo', { timeout: 20_000 });

  // The bottom side, turned over about the board's middle: on the same place, but left out of the job.
  await page.getByRole('button', { name: 'Make bottom side' }).click();
  await expect(panel(page)).toContainText('Board demo (bottom)');
  await expect(sideChoice(page).locator('option:checked')).toHaveText('top side (demo)');
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('bottom-made-left-out.png') });
  await panel(page).screenshot({ path: info.outputPath('side-choice.png') });

  // The question says the side, in the dry run and beside where the job lands.
  await ask(page);
  await expect(sidesLine(page)).toHaveText('sides: the top side of board demo. The other side is left out, for once the board is turned over');
  await expect(sidesLine(page)).toHaveAttribute('data-level', 'ok');
  await expect(question(page).getByText(/mm\): the top side of board demo\./)).toBeVisible();
  await question(page).screenshot({ path: info.outputPath('question-top-side.png') });
  await question(page).getByRole('button', { name: 'Cancel' }).click();

  // The other side chosen in the board's panel: the top side is left out.
  await sideChoice(page).selectOption({ label: 'bottom side (demo (bottom))' });
  await expect(sideChoice(page).locator('option:checked')).toHaveText('bottom side (demo (bottom))');
  await ask(page);
  await expect(sidesLine(page)).toHaveText(/^sides: the bottom side of board demo\./);
  await expect(question(page).getByText(/mm\): the bottom side of board demo\./)).toBeVisible();
  await question(page).getByRole('button', { name: 'Cancel' }).click();

  // A project saved before, with both sides in the job (no side left out), opened again.
  const download = page.waitForEvent('download');
  await page.getByRole('button', { name: 'Save', exact: true }).click();
  const path = info.outputPath('both-sides.uv-project.json');
  await (await download).saveAs(path);
  const project = JSON.parse(readFileSync(path, 'utf8'));
  for (const o of project.objects) delete o.leftOut;
  writeFileSync(path, JSON.stringify(project));
  await page.getByTestId('project-file').setInputFiles(path);
  await expect(page.getByText('Opened both-sides.uv-project.json')).toBeVisible();
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('both-sides-on-top.png') });

  // The dry run says it and stops the job; the question offers to leave one side out.
  await ask(page);
  await expect(sidesLine(page)).toHaveText('sides: board demo: both sides are in the job, exposed on top of each other. A board is exposed one side at a time: leave one out');
  await expect(sidesLine(page)).toHaveAttribute('data-level', 'error');
  await expect(question(page).getByText('Not exposed: fix what is marked above.')).toBeVisible();
  await expect(question(page).getByText(/mm\): both sides of board demo\./)).toBeVisible();
  const offer = question(page).getByRole('group', { name: 'One side of board demo' });
  await expect(offer.getByRole('button')).toHaveText(['Expose the top side only', 'Expose the bottom side only']);
  await question(page).screenshot({ path: info.outputPath('question-both-sides.png') });
  await offer.getByRole('button', { name: 'Expose the top side only' }).click();

  // Checked again with the bottom side left out: nothing stops it now.
  await expect(sidesLine(page)).toHaveText(/^sides: the top side of board demo\./, { timeout: 30_000 });
  await expect(offer).toHaveCount(0);
  await expect(question(page).getByRole('button', { name: /^Expose (now|anyway)$/ })).toBeVisible();
  await question(page).screenshot({ path: info.outputPath('question-top-side-chosen.png') });
  await question(page).getByRole('button', { name: 'Cancel' }).click();
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('top-side-chosen.png') });
});
