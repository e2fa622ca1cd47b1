// The machine's dashboards on the simulated printer: thermal history, position and jog, the probe and
// the mesh, LEDs and link, and the settings read from and saved to the printer.
import { expect, test, type Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';

async function open(page: Page) {
  await page.goto('/?simSpeed=20');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
}

const position = async (page: Page) => {
  const m = /X (-?[\d.]+) Y (-?[\d.]+) Z (-?[\d.]+)/.exec((await page.getByTestId('position').textContent()) ?? '');
  return m ? [Number(m[1]), Number(m[2]), Number(m[3])] : null;
};

test('the thermal chart draws the six sensors with their limits as reports arrive', async ({ page }, info) => {
  await open(page);
  const chart = page.getByTestId('thermal-chart');
  await expect(chart.locator('canvas')).toHaveCount(1);
  await expect(chart).toHaveAttribute('data-samples', /^([3-9]|\d\d+)$/, { timeout: 10_000 });
  await expect(chart.locator('.u-legend')).toHaveCount(0); // the sensors' table above is the one legend
  for (let i = 0; i < 6; i++) await expect(page.getByTestId(`temp-${i}`)).toHaveText(/^\d+\.\d °C$/);
  // The limits are drawn: the LEDs' 55 °C line in T0's colour crosses the plot.
  const limitDrawn = await chart.locator('canvas').evaluate((c: HTMLCanvasElement) => {
    const d = c.getContext('2d')!.getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 0x7b) < 12 && Math.abs(d[i + 1] - 0x2f) < 12 && Math.abs(d[i + 2] - 0xf7) < 12) n++;
    return n;
  });
  expect(limitDrawn).toBeGreaterThan(50);
  await expect(page.getByTestId('thermal-warning')).toHaveCount(0); // a machine at rest warms no sensor
  await page.screenshot({ path: info.outputPath('thermal.png'), fullPage: true });
});

test('homes, goes to a point, jogs by steps and held, releases, and self-tests', async ({ page }, info) => {
  test.setTimeout(120_000);
  await open(page);
  await page.getByTestId('tab-position').click();
  await page.getByTestId('home').click();
  await expect.poll(() => position(page), { timeout: 30_000 }).toEqual([0, 0, 0]);
  await page.getByTestId('goto-x').fill('50');
  await page.getByTestId('goto-y').fill('60');
  await page.getByTestId('goto-z').fill('5');
  await page.getByTestId('goto').click();
  await expect.poll(() => position(page), { timeout: 30_000 }).toEqual([50, 60, 5]);

  await page.getByTestId('jog-mode').selectOption('10');
  await page.getByTestId('jog-X+').click();
  await expect.poll(() => position(page), { timeout: 30_000 }).toEqual([60, 60, 5]);

  // Held: the head runs while the button is down and stops when it is let go.
  await page.getByTestId('jog-mode').selectOption('slow');
  const jog = page.getByTestId('jog-Y+');
  await jog.hover();
  await page.mouse.down();
  await expect.poll(async () => (await position(page))![1], { timeout: 10_000 }).toBeGreaterThan(61);
  await page.mouse.up();
  await page.waitForTimeout(600);
  const stopped = await position(page);
  await page.waitForTimeout(600);
  expect(await position(page)).toEqual(stopped);
  await expect(page.getByTestId('head-dot')).toBeVisible();
  await page.screenshot({ path: info.outputPath('position.png'), fullPage: true });

  await page.getByTestId('self-test-quick').click();
  for (const a of ['x', 'y']) await expect(page.getByTestId(`self-test-${a}`)).toHaveText('pass', { timeout: 60_000 });

  await page.getByTestId('release-motors').click();
  await expect(page.getByTestId('console-log')).toContainText('M18');
});

test('deploys, stows and tests the probe, maps the bed twice and compares', async ({ page }, info) => {
  test.setTimeout(180_000);
  await open(page);
  await page.getByTestId('tab-probe').click();
  await page.getByTestId('probe-deploy').click();
  await expect(page.getByTestId('probe-state')).toHaveText('deployed');
  await page.getByTestId('probe-stow').click();
  await expect(page.getByTestId('probe-state')).toHaveText('stowed');

  await page.getByTestId('tab-position').click();
  await page.getByTestId('home').click();
  await page.getByTestId('goto-x').fill('100');
  await page.getByTestId('goto-y').fill('100');
  await page.getByTestId('goto-z').fill('5');
  await page.getByTestId('goto').click();
  await page.getByTestId('tab-probe').click();
  await page.getByTestId('probe-deploy').click();
  await page.getByTestId('probe-test').click();
  await expect(page.getByTestId('probe-z')).toHaveText(/^last Z -?\d+\.\d{3} mm$/, { timeout: 30_000 });
  await page.getByTestId('probe-stow').click();

  await page.getByTestId('mesh-probe').click();
  await expect(page.getByTestId('mesh-map')).toBeVisible({ timeout: 90_000 });
  await expect(page.getByTestId('mesh-stats')).toContainText(/range \d+\.\d{3} mm [\s\S]* over 3 × 3 points/);
  await expect(page.getByTestId('mesh-compare')).toBeDisabled();
  await page.getByTestId('mesh-probe').click();
  await expect(page.getByTestId('mesh-compare')).toBeEnabled({ timeout: 90_000 });
  await page.getByTestId('mesh-compare').check();
  await expect(page.getByTestId('mesh-stats')).toContainText('Change since the previous mesh');
  await page.screenshot({ path: info.outputPath('mesh.png'), fullPage: true });

  // Probing turned leveling on: the dry run holds a drawing in the bed's corner, outside the
  // probed points (10 mm in from the edges), against the mesh, and asks before exposing it.
  await drawFilledRectangle(page, [0.28, 0.105], [0.295, 0.12]); // about 3–9 mm from the bed's corner
  await page.getByTestId('expose-drawing').click();
  const mesh = page.getByTestId('dry-run').locator('li', { hasText: /^mesh:/ });
  await expect(mesh).toHaveAttribute('data-level', 'warning');
  await expect(mesh).toContainText('outside the probed mesh');
  await expect(page.getByTestId('expose-anyway')).toBeVisible();
});

test('shows the LEDs and the link, and settings read, checked, applied and saved', async ({ page }, info) => {
  await open(page);
  await page.getByTestId('tab-link').click();
  await expect(page.getByTestId('led-state')).toHaveAttribute('data-lit', 'false');
  await expect(page.getByTestId('link-health')).toContainText(/\d+ lines, 0 resends/);

  await page.getByTestId('tab-settings').click();
  const travel = page.getByTestId('setting-speed.travel');
  await expect(travel).toHaveValue('100');
  await travel.fill('9999');
  await expect(page.getByTestId('settings-invalid')).toContainText('Travel speed: out of range');
  await expect(page.getByTestId('settings-apply')).toBeDisabled();
  await travel.fill('120');
  await page.getByTestId('settings-apply').click();
  await expect(page.getByTestId('console-log')).toContainText('M850 speed.travel 120');
  await page.getByTestId('settings-save').click();
  await expect(page.getByTestId('console-log')).toContainText('echo:Settings stored');
  await expect(travel).toHaveValue('120');
  await page.screenshot({ path: info.outputPath('settings.png'), fullPage: true });

  // Saved on the printer: a restart (reopening the link) reads it back.
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('tab-settings').click();
  await expect(page.getByTestId('setting-speed.travel')).toHaveValue('120');
});
