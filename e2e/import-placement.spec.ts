// Issue 17, item 12: each new import lands where it is visible and free, not on the one before.
import { expect, test } from '@playwright/test';
import { bmpFile, halfBlack } from '../app/src/studio/image/picture-files.fixture';

test('three imports of a picture land side by side in view, none on another', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const boxes: { x: number; y: number; w: number; h: number }[] = [];
  for (let i = 0; i < 3; i++) {
    // 40 × 20 pixels at 1000 a metre: 40 × 20 mm.
    const bmp = Buffer.from(bmpFile(40, 20, halfBlack(40), { x: 1000, y: 1000 }));
    await page.getByLabel('Import artwork (SVG, PNG, JPG, BMP, GIF)').setInputFiles({ name: `logo-${i}.bmp`, mimeType: 'image/bmp', buffer: bmp });
    const panel = page.getByRole('region', { name: 'Selected object' });
    await expect(panel).toContainText(`logo-${i}.bmp`);
    const field = async (name: string) => Number(await page.getByTestId(`object-${name}`).inputValue());
    boxes.push({ x: await field('x'), y: await field('y'), w: await field('w'), h: await field('h') });
  }
  for (let i = 0; i < boxes.length; i++)
    for (let j = 0; j < i; j++) {
      const [a, b] = [boxes[i], boxes[j]];
      expect(a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h, `import ${i} on import ${j}`).toBe(false);
    }
  // All on the 200 × 200 mm bed that the fitted view shows whole.
  for (const b of boxes) expect(b.x >= 0 && b.y >= 0 && b.x + b.w <= 200 && b.y + b.h <= 200).toBe(true);
  await page.getByRole('region', { name: 'Drawing' }).screenshot({ path: info.outputPath('three-imports.png') });
});
