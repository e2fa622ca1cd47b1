// Test-only: draws on the studio's canvas as a person would, with the pointer.
import type { Page } from '@playwright/test';

/** A filled rectangle between two points given as shares of the canvas's width and height. */
export async function drawFilledRectangle(page: Page, from: [number, number], to: [number, number]): Promise<void> {
  await page.getByTestId('tool-rect-filled').click();
  const box = (await page.getByTestId('editor-canvas').boundingBox())!;
  await page.mouse.move(box.x + box.width * from[0], box.y + box.height * from[1]);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * to[0], box.y + box.height * to[1], { steps: 4 });
  await page.mouse.up();
}
