// Issue 17, item 8: choose Text, click the bed, type: the text goes where the user clicked, and
// Space is a letter, not a page scroll.
import { expect, test } from '@playwright/test';

test('the Text tool places typed words at the click', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByRole('toolbar', { name: 'Tools' }).getByRole('button', { name: 'Text', exact: true }).click();
  const canvas = page.getByRole('region', { name: 'Drawing' }).locator('canvas');
  const box = (await canvas.boundingBox())!;
  const scrolled = await page.evaluate(() => window.scrollY);
  const click = { x: box.x + box.width * 0.4, y: box.y + box.height * 0.35 };
  await page.mouse.click(click.x, click.y);
  await page.keyboard.type('Hi PCB 7');
  await expect(page.getByRole('textbox', { name: 'Text', exact: true })).toHaveValue('Hi PCB 7');
  expect(await page.evaluate(() => window.scrollY)).toBe(scrolled); // Space did not scroll the page
  expect(Number(await page.getByTestId('object-h').inputValue())).toBe(5);
  expect(Number(await page.getByTestId('object-w').inputValue())).toBeGreaterThan(10); // eight glyphs at 5 mm
  await page.keyboard.press('Enter'); // done typing
  // The words lie where the click was: they start at it and grow to the right. With the select
  // tool, a click just right of it picks the text; one just left of it picks nothing.
  await page.getByRole('button', { name: 'Select', exact: true }).click();
  const empty = { x: box.x + box.width * 0.9, y: box.y + box.height * 0.9 };
  await page.mouse.click(empty.x, empty.y);
  await expect(page.getByTestId('object-panel')).toHaveCount(0);
  await page.mouse.click(click.x + 6, click.y);
  await expect(page.getByTestId('object-panel')).toHaveAttribute('data-kind', 'text');
  await page.mouse.click(empty.x, empty.y);
  await page.mouse.click(click.x - 6, click.y);
  await expect(page.getByTestId('object-panel')).toHaveCount(0);
  await page.mouse.click(click.x + 6, click.y);
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('typed-text.png') });
  // After typing, the tool keys work again (B is the brush).
  await page.keyboard.press('b');
  await expect(page.getByRole('button', { name: 'Brush' })).toHaveAttribute('aria-pressed', 'true');
});
