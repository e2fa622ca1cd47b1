// Test-only: what the studio's canvas shows, read as a person would see it: a pixel's colour, whether
// it shows a dose, and where a point of the bed in mm lies on the canvas with the bed fitted to the view.
import type { Page } from '@playwright/test';

/** The colour the canvas shows at a point of its box (CSS pixels). */
export async function pixel(page: Page, x: number, y: number): Promise<[number, number, number]> {
  return page.getByTestId('editor-canvas').evaluate((c: HTMLCanvasElement, [x, y]) => {
    const dpr = window.devicePixelRatio || 1;
    const d = c.getContext('2d')!.getImageData(Math.round(x * dpr), Math.round(y * dpr), 1, 1).data;
    return [d[0], d[1], d[2]] as [number, number, number];
  }, [x, y]);
}

/** UV violet: neither the white bed nor the grey around it. */
export const isDose = ([r, g]: number[]) => g < r - 15;

/** Where a point of the bed, in mm, is on the canvas (CSS pixels from its corner), the bed fitted to the view. */
export async function bedPoint(page: Page, mmX: number, mmY: number): Promise<{ x: number; y: number }> {
  const [cols, rows, pitchUm] = (/^(\d+) × (\d+) cells of (\d+) µm/.exec((await page.getByTestId('grid-size').textContent())!) ?? []).slice(1).map(Number);
  const box = (await page.getByTestId('editor-canvas').boundingBox())!;
  const ruler = 22, margin = 16, aw = box.width - ruler, ah = box.height - ruler;
  const scale = Math.min((aw - 2 * margin) / cols, (ah - 2 * margin) / rows);
  const cell = (mm: number) => (mm * 1000) / pitchUm;
  return { x: ruler + aw / 2 + (cell(mmX) - cols / 2) * scale, y: ruler + ah / 2 + (cell(mmY) - rows / 2) * scale };
}
