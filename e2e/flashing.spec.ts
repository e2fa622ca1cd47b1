// The Firmware view flashes the real bootloaders, each running in simavr behind the fake USB cable
// (e2e/bootloader-rig.ts): the image is written and read back, then the new firmware answers.
import { readFileSync } from 'node:fs';
import { expect, test, type Page } from '@playwright/test';
import { IMAGES, SimulatedBoard } from './bootloader-rig';
import { installFakeSerial } from './fake-serial';

// Generous: the rig keeps to the wall clock only while the machine has a core for it, and the specs
// must pass on a loaded one too (each reply also crosses Playwright's page bindings).
test.describe.configure({ timeout: 300_000 });

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

test('the published Nano image goes into Optiboot, is read back, and the flashed Nano answers V, S and T', async ({ page }) => {
  board = new SimulatedBoard('optiboot');
  await openFirmwareView(page, board);
  await expect(page.getByTestId('firmware-plug-in')).toContainText('Unplug the Nano from the Mega');
  // The image this machine built, published beside the app with its manifest (scripts/firmware-manifest.mjs).
  await expect(page.getByTestId('firmware-image')).toContainText(/^\d+\.\d+\.\d+ \(Debian avr-gcc, this machine\)$/);
  await expect(page.getByTestId('firmware-lacks')).toHaveCount(0);
  await page.getByTestId('firmware-flash').click();
  await expect(page.getByTestId('firmware-status')).toHaveAttribute('data-state', 'done', { timeout: 280_000 });
  await expect(page.getByTestId('firmware-version')).toContainText(/^\d+\.\d+\.\d+ \(Nano link protocol 1\)$/);
  await expect(page.getByTestId('firmware-answers')).toContainText(/S:\d+, T:[\d,-]+/);
});

test('the Mega image goes into the STK500 v2 bootloader, is read back, and the flashed Mega answers M115', async ({ page }) => {
  test.setTimeout(720_000); // 148 KB written and read back at 115200 baud: about 1 min unloaded, 4 on a loaded machine
  board = new SimulatedBoard('stk500v2');
  await openFirmwareView(page, board);
  await page.getByTestId('firmware-board').selectOption('mega');
  await expect(page.getByTestId('firmware-plug-in')).toContainText('DIP switches 3 and 4 ON');
  // The Mega image built here lacks the SD card, and says so; the user's own file takes the same path.
  await expect(page.getByTestId('firmware-lacks')).toContainText('has no SD card support');
  await flashFile(page, 'mega', IMAGES.mega);
  await expect(page.getByTestId('firmware-status')).toHaveAttribute('data-state', 'done', { timeout: 700_000 });
  await expect(page.getByTestId('firmware-version')).toHaveText(/^UVExposure \d+\.\d+\.\d+ \(Mega\)$/);
});

test('the old Nano bootloader at 57600 takes the Nano image too', async ({ page }) => {
  board = new SimulatedBoard('atmegaboot');
  await openFirmwareView(page, board);
  await flashFile(page, 'nano-old', IMAGES.nano);
  await expect(page.getByTestId('firmware-status')).toHaveAttribute('data-state', 'done', { timeout: 280_000 });
  await expect(page.getByTestId('firmware-version')).toContainText('(Nano link protocol 1)');
});

test('a Nano plugged in where the Mega was picked is named, nothing is written, and its bootloader still answers', async ({ page }) => {
  board = new SimulatedBoard('optiboot');
  await openFirmwareView(page, board);
  await flashFile(page, 'mega', IMAGES.mega);
  await expect(page.getByTestId('firmware-error')).toHaveAttribute('data-failure', 'wrong-chip', { timeout: 120_000 });
  await expect(page.getByTestId('firmware-error')).toContainText('has an ATmega328P, not the ATmega2560 of the Mega 2560');
  expect(await board.bootloaderAnswers()).toBe(true);
});

test('an image built for the other chip, and a damaged file, are refused before any port is opened', async ({ page }) => {
  board = new SimulatedBoard('optiboot');
  await openFirmwareView(page, board);
  await flashFile(page, 'nano', IMAGES.mega);
  await expect(page.getByTestId('firmware-error')).toContainText('built for the ATmega2560');
  const hex = readFileSync(IMAGES.nano, 'latin1').split('\n');
  hex[5] = hex[5].slice(0, 12) + (hex[5][12] === '0' ? '1' : '0') + hex[5].slice(13); // one digit changed
  await page.getByTestId('firmware-file').setInputFiles({ name: 'nano.hex', mimeType: 'text/plain', buffer: Buffer.from(hex.join('\n')) });
  await expect(page.getByTestId('firmware-image-error')).toHaveText('nano.hex: line 6 fails its checksum: the file is damaged.');
  await expect(page.getByTestId('firmware-flash')).toBeDisabled();
  expect(board.sent).toBe(0);
  expect(await board.bootloaderAnswers()).toBe(true);
});

test('a cable pulled mid-write says the bootloader is still there, and flashing again works', async ({ page }) => {
  test.setTimeout(600_000); // two flashes
  board = new SimulatedBoard('optiboot');
  await openFirmwareView(page, board);
  board.pullAfter = 8000; // about a third of the image
  await flashFile(page, 'nano', IMAGES.nano);
  const error = page.getByTestId('firmware-error');
  await expect(error).toHaveAttribute('data-failure', 'cable-pulled', { timeout: 280_000 });
  await expect(error).toContainText(/while writing page \d+ of \d+.*bootloader.*still there.*Plug the board back in and flash again/);
  board.plugIn();
  await page.getByTestId('firmware-flash').click();
  await expect(page.getByTestId('firmware-status')).toHaveAttribute('data-state', 'done', { timeout: 280_000 });
  await expect(page.getByTestId('firmware-answers')).toContainText(/S:\d+, T:/);
});
