// Issue 29, item 14, on the machine's side: settings say in words what they once left to
// "(planner.md)" and "(job.md)"; Reverse X/Y/Z are checkboxes that still write 0 or 1; homing says
// "Homing…" while the move that asked for it waits; the mesh comparison says why it is closed.
import { expect, test, type Page } from '@playwright/test';

async function open(page: Page, speed: number) {
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto(`/?simSpeed=${speed}`);
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
}

test('settings name no file, and Reverse X is a checkbox that writes 1 and 0', async ({ page }, info) => {
  await open(page, 20);
  await page.getByRole('tab', { name: 'Settings' }).click();
  const panel = page.getByRole('tabpanel');
  await expect(panel.getByLabel('LED 0 offset')).toHaveAccessibleDescription(/from the head origin, in cells: with the head over a cell, LED 0 exposes the cell dx across and dy down from it/);
  await expect(panel.getByLabel('LED 2 irradiance')).toHaveAccessibleDescription(/a dose asked in µJ\/cm² becomes an exposure time from it/);
  await expect(panel.getByLabel('Thermal compensation')).toHaveAccessibleDescription(/each exposure is lengthened by c × 0\.01 % for every °C/);
  for (const about of await panel.locator('small').allTextContents()) expect(about).not.toMatch(/\.md\b/);
  await panel.getByRole('group', { name: 'LEDs' }).screenshot({ path: info.outputPath('led-settings.png') });

  const reverse = panel.getByRole('checkbox', { name: 'Reverse X' });
  await expect(reverse).not.toBeChecked();
  await expect(panel.getByRole('checkbox', { name: 'Reverse Y' })).toBeVisible();
  await expect(panel.getByRole('checkbox', { name: 'Reverse Z' })).toBeVisible();
  await expect(reverse).toHaveAccessibleDescription(/reverse the X direction pin: ticked writes 1, unticked 0/);
  await reverse.check();
  await panel.getByRole('button', { name: 'Apply', exact: true }).click();
  const log = page.getByRole('region', { name: 'Console' }).getByRole('list');
  await expect(log.getByText(/> M850 invert\.x 1$/)).toBeVisible();
  await expect(log.getByText(/M850 invert\.x 1$/).last()).toBeVisible(); // M503 read it back
  await expect(reverse).toBeChecked();
  await panel.getByRole('group', { name: 'Motion' }).screenshot({ path: info.outputPath('reverse-x-on.png') });
  await reverse.uncheck();
  await panel.getByRole('button', { name: 'Apply', exact: true }).click();
  await expect(log.getByText(/> M850 invert\.x 0$/)).toBeVisible();
  await expect(reverse).not.toBeChecked();
});

test('a jog that must home first says "Homing…" while it waits, and the jog buttons wait too', async ({ page }, info) => {
  await open(page, 1);
  await page.getByRole('tab', { name: 'Position' }).click();
  const panel = page.getByRole('tabpanel');
  await panel.getByRole('button', { name: 'X+', exact: true }).click();
  await page.getByRole('dialog').getByRole('button', { name: 'Home and continue' }).click();
  await expect(panel.getByRole('status')).toHaveText('Homing… every axis to its endstop. Jog and Go open again when it is done.', { timeout: 2000 });
  await expect(page.getByTestId('job-state').getByRole('status')).toHaveText('Homing… Then: Jog X.');
  await expect(panel.getByRole('button', { name: 'X+', exact: true })).toBeDisabled();
  await expect(panel.getByRole('button', { name: 'X+', exact: true })).toHaveAttribute('title', /the machine is homing/);
  await page.screenshot({ path: info.outputPath('homing.png'), fullPage: true });
  // Then the jog runs, and the signs go.
  await expect(panel.getByRole('status')).toHaveCount(0, { timeout: 30_000 });
  await expect(page.getByTestId('job-state')).toHaveText('No job.');
  await expect(page.getByTestId('position')).toContainText(/X 1\.000 Y 0\.000/, { timeout: 10_000 });
});

test('"compare with the previous mesh" says why it is closed, until there are two meshes alike', async ({ page }, info) => {
  test.setTimeout(240_000);
  await open(page, 40);
  await page.getByRole('tab', { name: 'Probe & mesh' }).click();
  const panel = page.getByRole('tabpanel');
  const compare = panel.getByRole('checkbox', { name: 'compare with the previous mesh' });
  await expect(compare).toBeDisabled();
  await expect(compare).toHaveAccessibleDescription(/^Compare: no mesh yet: probe the bed, then probe it again to compare\.$/);
  await panel.getByRole('button', { name: 'Probe the bed' }).click();
  await page.getByRole('dialog').getByRole('button', { name: 'Home and continue' }).click();
  await expect(panel.getByTestId('mesh-stats')).toContainText('over 3 × 3 points', { timeout: 90_000 });
  await expect(compare).toHaveAccessibleDescription(/^Compare: one mesh so far: probe the bed again, and the change since this one is shown\.$/);
  await panel.screenshot({ path: info.outputPath('one-mesh.png') });

  await panel.getByLabel('Points').selectOption('4');
  await panel.getByRole('button', { name: 'Probe the bed' }).click();
  await expect(panel.getByTestId('mesh-stats')).toContainText('over 4 × 4 points', { timeout: 90_000 });
  await expect(compare).toBeDisabled();
  await expect(compare).toHaveAccessibleDescription('Compare: the previous mesh has 3 × 3 points and this one 4 × 4: probe with the same points to compare.');
  await panel.screenshot({ path: info.outputPath('unlike-meshes.png') });

  await panel.getByRole('button', { name: 'Probe the bed' }).click();
  await expect(compare).toBeEnabled({ timeout: 90_000 });
  await expect(panel.getByText(/^Compare:/)).toHaveCount(0);
  await compare.check();
  await expect(panel.getByTestId('mesh-stats')).toContainText('Change since the previous mesh');
  await panel.screenshot({ path: info.outputPath('compared.png') });
});
