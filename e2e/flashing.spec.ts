// The Firmware view flashes the real bootloaders, each running in simavr behind the fake USB cable
// (e2e/bootloader-rig.ts): the image is written and read back, then the new firmware answers.
import { expect, test, type Page } from '@playwright/test';
import { IMAGES, SimulatedBoard } from './bootloader-rig';
import { installFakeSerial } from './fake-serial';

test.describe.configure({ timeout: 120_000 });

let board: SimulatedBoard | null = null;
test.afterEach(() => board?.stop());

async function openFirmwareView(page: Page, b: SimulatedBoard) {
  await installFakeSerial(page, b.attach, 'port', [115200, 57600]);
  await page.goto('/');
  await page.getByTestId('tab-firmware').click();
  await expect(page.getByTestId('firmware-view')).toBeVisible();
}

async function flashFile(page: Page, boardId: string, file: string) {
  await page.getByTestId('firmware-board').selectOption(boardId);
  await page.getByTestId('firmware-source').selectOption('file');
  await page.getByTestId('firmware-file').setInputFiles(file);
  await page.getByTestId('firmware-flash').click();
}

test('the Nano image goes into Optiboot, is read back, and the flashed Nano answers V, S and T', async ({ page }) => {
  board = new SimulatedBoard('optiboot');
  await openFirmwareView(page, board);
  await expect(page.getByTestId('firmware-plug-in')).toContainText('Unplug the Nano from the Mega');
  await flashFile(page, 'nano', IMAGES.nano);
  await expect(page.getByTestId('firmware-status')).toHaveAttribute('data-state', 'done', { timeout: 90_000 });
  await expect(page.getByTestId('firmware-version')).toContainText(/^\d+\.\d+\.\d+ \(Nano link protocol 1\)$/);
  await expect(page.getByTestId('firmware-answers')).toContainText(/S:\d+, T:[\d,-]+/);
});
