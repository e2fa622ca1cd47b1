// Projects: saved as a file and opened again, autosaved and restored after a reload, recent
// projects, a damaged file refused with the drawing kept, and the material test made and exposed.
import { expect, test, type Page } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { drawFilledRectangle } from './draw';

async function placeText(page: Page, words: string) {
  await page.getByTestId('tool-text').click();
  await page.getByTestId('text-draft').fill(words);
  const box = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.click(box.x + box.width * 0.5, box.y + box.height * 0.7);
  await expect(page.getByTestId('object-panel')).toHaveAttribute('data-kind', 'text');
}

test('saves a project as a file, starts a new one, and opens the file again with its text and cells', async ({ page }, info) => {
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.45, 0.45]);
  await placeText(page, 'rev 3');
  await page.getByTestId('project-name').fill('front panel');

  const download = page.waitForEvent('download');
  await page.getByTestId('project-save').click();
  const file = await download;
  expect(file.suggestedFilename()).toBe('front panel.uv-project.json');
  const path = info.outputPath('saved.uv-project.json');
  await file.saveAs(path);
  const saved = JSON.parse(readFileSync(path, 'utf8'));
  expect(saved).toMatchObject({ format: 'uv-exposure-project', version: 2, name: 'front panel', exposure: { fullMs: 4, strategy: 'auto' } });
  expect(saved.objects).toEqual([expect.objectContaining({ kind: 'text', text: 'rev 3' })]);
  expect(typeof saved.paint.cells).toBe('string');

  await page.getByTestId('project-new').click();
  await expect(page.getByTestId('project-name')).toHaveValue('Untitled');
  await expect(page.getByTestId('expose-drawing')).toBeDisabled();

  await page.getByTestId('project-file').setInputFiles(path);
  await expect(page.getByTestId('project-status')).toHaveText('Opened saved.uv-project.json');
  await expect(page.getByTestId('project-name')).toHaveValue('front panel');
  await expect(page.getByTestId('expose-drawing')).toBeEnabled();
  // The text came back as an object that can be selected and edited.
  await page.getByTestId('tool-select').click();
  const box = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.click(box.x + box.width * 0.5, box.y + box.height * 0.7);
  await expect(page.getByTestId('object-text')).toHaveValue('rev 3');
  // Undo has nothing to take back: the history starts with the project.
  await expect(page.getByTestId('undo')).toBeDisabled();

  await page.getByTestId('project-recent').click();
  await expect(page.getByTestId('recent-front panel')).toBeVisible();
  await page.screenshot({ path: info.outputPath('opened.png'), fullPage: true });
});

test('a damaged project file is refused, saying what is wrong, and the drawing stays', async ({ page }) => {
  await page.goto('/?simSpeed=40');
  await drawFilledRectangle(page, [0.4, 0.4], [0.45, 0.45]);
  await page.getByTestId('project-file').setInputFiles({ name: 'broken.json', mimeType: 'application/json', buffer: Buffer.from('{"format":"uv-exposure-project","version":1,"name":"x","machine":{"bedMm":{"x":200,"y":200},"pitchUm":{"x":50,"y":50}},"exposure":{"fullMs":4,"strategy":"serpentine"},"paint":{"cols":4000,"rows":4000,"cells":"AAAA"},"objects":[]}') });
  await expect(page.getByTestId('project-error')).toHaveText(/^This project cannot be opened: paint\.cells /);
  await expect(page.getByTestId('view-preview')).toBeEnabled(); // the rectangle is still there
  await page.getByTestId('project-file').setInputFiles({ name: 'notes.json', mimeType: 'application/json', buffer: Buffer.from('{"grid": [1, 2') });
  await expect(page.getByTestId('project-error')).toHaveText(/^This project cannot be opened: this is not a project file/);
  await expect(page.getByTestId('view-preview')).toBeEnabled();
});

test('autosaves after an edit and restores it when the app is opened again', async ({ page }) => {
  await page.goto('/?simSpeed=40');
  await drawFilledRectangle(page, [0.4, 0.4], [0.45, 0.45]);
  await page.getByTestId('project-name').fill('kept');
  await expect(page.getByTestId('project-autosaved')).toHaveText(/^Autosaved at /);
  await page.reload();
  await expect(page.getByTestId('project-status')).toHaveText(/^Restored from the autosave of /);
  await expect(page.getByTestId('project-name')).toHaveValue('kept');
  await expect(page.getByTestId('view-preview')).toBeEnabled();
});

test('makes a √2 wedge as a project and exposes it; the project is kept before the job', async ({ page }, info) => {
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('material-test-open').click();
  await page.getByTestId('material-steps').fill('4');
  await page.getByTestId('material-longest').fill('2');
  await page.getByTestId('material-patch').fill('1.5');
  await expect(page.getByTestId('material-times')).toHaveText('0.71 ms, 1.00 ms, 1.41 ms, 2.00 ms');
  await page.getByTestId('material-make').click();
  await expect(page.getByTestId('material-test')).toBeHidden();
  await expect(page.getByTestId('project-name')).toHaveValue('Material test (√2 wedge, 4 steps)');
  await expect(page.getByTestId('project-status')).toHaveText(/^Made Material test/);
  await expect(page.getByTestId('full-ms')).toHaveValue('2');
  await page.screenshot({ path: info.outputPath('material-test.png'), fullPage: true });

  await page.getByTestId('expose-drawing').click();

  await page.getByRole('dialog').getByRole('button', { name: 'Expose now' }).click(); // the one confirmation (issue 17, item 4)
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', /running|done/, { timeout: 30_000 });
  await page.getByTestId('project-recent').click();
  await expect(page.getByTestId('recent-Material test (√2 wedge, 4 steps)')).toBeVisible();
  await expect(page.locator('.recent li').first()).toContainText('before a job');
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'done', { timeout: 90_000 });
});
