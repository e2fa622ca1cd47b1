// The planner's module missing from the server (a redeploy the open page has not caught up with, a
// hub whose flash lost the file): the preview says which file it could not load, and plans once it can.
import { expect, test } from '@playwright/test';
import { drawFilledRectangle } from './draw';

// The work worker fetches the module: routed for the whole context, and with no service worker to answer first.
test.use({ serviceWorkers: 'block' });

test('says the planner module could not be loaded, and plans on "Plan again" once it can', async ({ page, context }, info) => {
  let refused = 0;
  await context.route('**/planner*.wasm', (route) => {
    refused++;
    return route.fulfill({ status: 404, body: 'not found' });
  });
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await drawFilledRectangle(page, [0.4, 0.4], [0.43, 0.42]);
  await page.getByTestId('view-preview').click();
  await expect(page.getByTestId('preview-empty')).toHaveText("Could not plan: the planner's module (planner.wasm) could not be loaded: HTTP 404. Reload the page if the app was updated");
  expect(refused).toBeGreaterThan(0);
  await page.screenshot({ path: info.outputPath('module-missing.png'), fullPage: true });

  await context.unroute('**/planner*.wasm');
  await page.getByTestId('preview-refresh').click();
  await expect(page.getByTestId('preview-summary')).toContainText(/\d+ (stops|passes) /);
  await expect(page.getByTestId('preview-empty')).toHaveCount(0);
});
