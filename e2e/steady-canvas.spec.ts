// Issue 17, item 9: nothing moves the canvas under the pointer: not the "Autosaved at…" line after
// the first edit, not a message about a project that cannot be opened.
import { expect, test } from '@playwright/test';
import { drawFilledRectangle } from './draw';

test('the canvas stays where it was when the autosave line and a project error appear', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const canvas = page.getByTestId('editor-canvas');
  const before = (await canvas.boundingBox())!;
  await drawFilledRectangle(page, [0.3, 0.3], [0.4, 0.4]);
  await expect(page.getByText(/^Autosaved at /)).toBeVisible();
  expect(await canvas.boundingBox()).toEqual(before);
  await page.screenshot({ path: info.outputPath('after-autosave.png') });
  await page.getByTestId('project-file').setInputFiles({ name: 'broken.uv-project.json', mimeType: 'application/json', buffer: Buffer.from('{}') });
  await expect(page.getByText(/cannot be opened/)).toBeVisible();
  expect(await canvas.boundingBox()).toEqual(before);
  await page.screenshot({ path: info.outputPath('after-error.png') });
});
