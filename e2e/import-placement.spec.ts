// Issue 17, item 12: each new import lands where it is visible and free, not on the one before.
import { expect, test } from '@playwright/test';

/** A w × h 24-bit BMP, its left half black. */
function halfBlackBmp(w: number, h: number): Buffer {
  const row = Math.ceil((w * 3) / 4) * 4;
  const b = Buffer.alloc(54 + row * h);
  b.write('BM', 0);
  b.writeUInt32LE(b.length, 2);
  b.writeUInt32LE(54, 10);
  b.writeUInt32LE(40, 14);
  b.writeInt32LE(w, 18);
  b.writeInt32LE(h, 22);
  b.writeUInt16LE(1, 26);
  b.writeUInt16LE(24, 28);
  b.writeUInt32LE(row * h, 34);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) b.fill(x < w / 2 ? 0 : 255, 54 + y * row + x * 3, 54 + y * row + x * 3 + 3);
  return b;
}

test('three imports of a picture land side by side in view, none on another', async ({ page }, info) => {
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  const boxes: { x: number; y: number; w: number; h: number }[] = [];
  for (let i = 0; i < 3; i++) {
    await page.getByLabel('Import a picture (JPG, PNG, GIF, BMP)').setInputFiles({ name: `logo-${i}.bmp`, mimeType: 'image/bmp', buffer: halfBlackBmp(40, 20) });
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
