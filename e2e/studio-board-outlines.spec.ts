// Issue 41 item 6: a board imported twice was placed edge to edge with the first, and the two boxes'
// outlines merged into one thick line, so where one board ended was lost. An import now keeps 2 mm from
// the objects already there, and each box's outline is a thin line of its own.
import { expect, test, type Page } from '@playwright/test';
import { bedPoint } from './canvas';
import { importBoard, openStudio, selected } from './boards';

const DEMO = ['demo-F_Cu.gbr', 'demo-B_Cu.gbr', 'demo-F_Mask.gbr', 'demo-Edge_Cuts.gbr', 'demo-PTH.drl'];

async function placedMm(page: Page) {
  const field = (name: RegExp) => selected(page).getByRole('spinbutton', { name });
  const [x, y, w, h] = await Promise.all([/^X\b/, /^Y\b/, /^W\b/, /^H\b/].map(async (n) => Number(await field(n).inputValue())));
  return { x, y, w, h };
}

/** The rows, from y0 to y1 (CSS px), where a strip of the canvas 24 px wide about x shows a line: runs of them, as [first, last]. */
async function lineRuns(page: Page, x: number, y0: number, y1: number): Promise<[number, number][]> {
  return page.getByTestId('editor-canvas').evaluate((c: HTMLCanvasElement, [x, y0, y1]) => {
    const dpr = window.devicePixelRatio || 1;
    const d = c.getContext('2d')!.getImageData(Math.round((x - 12) * dpr), Math.round(y0 * dpr), Math.round(24 * dpr), Math.round((y1 - y0) * dpr));
    const runs: [number, number][] = [];
    for (let row = 0; row < d.height; row++) {
      let line = false;
      for (let col = 0; col < d.width; col++) {
        const i = (row * d.width + col) * 4;
        if (d.data[i] + d.data[i + 1] + d.data[i + 2] < 3 * 235) line = true; // darker than the bed's white
      }
      const at = y0 + row / dpr;
      if (line && runs.length && runs.at(-1)![1] >= at - 1 / dpr - 1e-9) runs.at(-1)![1] = at;
      else if (line) runs.push([at, at]);
    }
    return runs;
  }, [x, y0, y1]);
}

test('a board imported twice lands 2 mm from the first, each outline a thin line of its own', async ({ page }, info) => {
  await openStudio(page);
  await importBoard(page, '', DEMO);
  await expect(selected(page)).toContainText('Board demo', { timeout: 20_000 });
  const first = await placedMm(page);
  await importBoard(page, '', DEMO);
  await expect(async () => expect(await placedMm(page)).not.toEqual(first)).toPass({ timeout: 20_000 });
  const second = await placedMm(page);

  // Apart by 2 mm on one axis, in line on the other.
  const apart = Math.max(second.x - (first.x + first.w), first.x - (second.x + second.w), second.y - (first.y + first.h), first.y - (second.y + second.h));
  expect(apart).toBeCloseTo(2, 1);

  // Nothing selected: only the boxes' own outlines are drawn between the boards.
  const canvas = page.getByTestId('editor-canvas');
  const box = (await canvas.boundingBox())!;
  const empty = await bedPoint(page, 20, 20);
  await canvas.click({ position: empty });
  await expect(selected(page)).toHaveCount(0);
  const [upper, lower] = first.y < second.y ? [first, second] : [second, first];
  expect(upper.x).toBe(lower.x);
  const from = await bedPoint(page, upper.x + upper.w / 2, upper.y + upper.h - 1);
  const to = await bedPoint(page, upper.x + upper.w / 2, lower.y + 1);
  await page.screenshot({ path: info.outputPath('two-boards.png'), clip: { x: box.x + from.x - 90, y: box.y + from.y - 60, width: 180, height: to.y - from.y + 120 } });
  const runs = await lineRuns(page, from.x, from.y, to.y);
  expect(runs, JSON.stringify(runs)).toHaveLength(2); // the upper box's bottom edge and the lower box's top edge
  for (const [a, b] of runs) expect(b - a, 'a thin line').toBeLessThanOrEqual(1);
  expect(runs[1][0] - runs[0][1], 'bed between the two lines (px)').toBeGreaterThanOrEqual(3);
});
