// The Firmware view's ESP path: the published ESP image (firmware and LittleFS) from the manifest, the
// board's DIP switches, and the hand-off to Espressif's esptool-js over the fake Web Serial. No ESP can
// run here: the port's far end is silent, so the library's connect must fail and the view say what to do.
import { createHash } from 'node:crypto';
import { writeFileSync } from 'node:fs';
import { expect, test } from '@playwright/test';
import { DEFAULT_CSV } from '../app/src/firmware/esp-partitions.test-helper';
import { installFakeSerial } from './fake-serial';

const firmware = Buffer.alloc(4096, 0xe9);
const littlefs = Buffer.alloc(8192, 0x00);
const sha = (b: Buffer) => createHash('sha256').update(b).digest('hex');
const MANIFEST = {
  images: [
    { board: 'esp8266', version: '0.1.0', built: 'PlatformIO', parts: [
      { file: 'esp8266-firmware.bin', offset: 0, sha256: sha(firmware), bytes: firmware.length },
      { file: 'esp8266-littlefs.bin', offset: 0x200000, sha256: sha(littlefs), bytes: littlefs.length },
    ] },
  ],
};

test('the ESP8266 image goes to esptool-js, which finds no ESP on a silent port, and the view says how to get its bootloader', async ({ page }) => {
  test.setTimeout(90_000);
  let opened = 0;
  let signals = 0;
  await installFakeSerial(page, () => ({ receive() {}, open: () => void opened++, signals: () => void signals++ }));
  await page.route('**/firmware/manifest.json', (route) => route.fulfill({ json: MANIFEST }));
  await page.route('**/firmware/esp8266-firmware.bin', (route) => route.fulfill({ body: firmware }));
  await page.route('**/firmware/esp8266-littlefs.bin', (route) => route.fulfill({ body: littlefs }));
  await page.goto('/');
  await page.getByTestId('tab-firmware').click();
  await page.getByTestId('firmware-board').selectOption('esp8266');
  await expect(page.getByTestId('firmware-plug-in')).toContainText('DIP switches 5, 6 and 7 ON');
  await expect(page.getByTestId('firmware-parts')).toHaveText(/esp8266-firmware\.bin at 0x0 \(4096 B\)\s*esp8266-littlefs\.bin at 0x200000 \(8192 B\)/);
  await page.getByTestId('firmware-flash').click();
  const error = page.getByTestId('firmware-error');
  await expect(error).toHaveAttribute('data-failure', 'no-bootloader', { timeout: 80_000 });
  await expect(error).toContainText('No ESP bootloader answered');
  expect(opened).toBeGreaterThan(0); // the library opened the port…
  expect(signals).toBeGreaterThan(0); // …and pulsed DTR and RTS to put the ESP in its bootloader
});

test('an ESP file that is not the one the manifest names is refused before any port is asked for', async ({ page }) => {
  let opened = 0;
  await installFakeSerial(page, () => ({ receive() {}, open: () => void opened++ }));
  await page.route('**/firmware/manifest.json', (route) => route.fulfill({ json: MANIFEST }));
  await page.route('**/firmware/esp8266-firmware.bin', (route) => route.fulfill({ body: Buffer.alloc(4096, 0xff) }));
  await page.route('**/firmware/esp8266-littlefs.bin', (route) => route.fulfill({ body: littlefs }));
  await page.goto('/');
  await page.getByTestId('tab-firmware').click();
  await page.getByTestId('firmware-board').selectOption('esp8266');
  await page.getByTestId('firmware-flash').click();
  await expect(page.getByTestId('firmware-image-error')).toContainText('esp8266-firmware.bin is not the file the manifest names');
  expect(opened).toBe(0);
});

test("an ESP32's own files go to esptool-js at their places; a file that is not what its place holds is refused before any port", async ({ page }, info) => {
  test.setTimeout(90_000);
  let opened = 0;
  await installFakeSerial(page, () => ({ receive() {}, open: () => void opened++ }));
  await page.route('**/firmware/manifest.json', (route) => route.fulfill({ json: { images: [] } })); // none published for it
  await page.goto('/');
  await page.getByTestId('tab-firmware').click();
  await page.getByTestId('firmware-board').selectOption('esp32');
  await page.getByTestId('firmware-source').selectOption('file');
  await expect(page.getByTestId('firmware-own-parts')).toContainText('firmware.bin at 0x10000 (up to 1310720 B)');
  await expect(page.getByTestId('firmware-flash')).toBeDisabled(); // nothing picked yet

  // A LittleFS image picked where the firmware goes, first without the partition table its places come from.
  const fs = Buffer.alloc(8192);
  fs.write('littlefs', 8, 'latin1');
  const fsPath = info.outputPath('littlefs.bin');
  writeFileSync(fsPath, fs);
  await page.getByTestId('firmware-esp-file-firmware.bin').setInputFiles(fsPath);
  await page.getByTestId('firmware-flash').click();
  await expect(page.getByTestId('firmware-image-error')).toContainText('Pick the partitions.bin your build produced too');
  const tablePath = info.outputPath('partitions.bin');
  writeFileSync(tablePath, DEFAULT_CSV);
  await page.getByTestId('firmware-esp-file-partitions.bin').setInputFiles(tablePath);
  await page.getByTestId('firmware-flash').click();
  await expect(page.getByTestId('firmware-image-error')).toContainText('littlefs.bin is no ESP firmware image (those begin with the byte 0xE9)');
  expect(opened).toBe(0);

  // The right files in their places: esptool-js opens the port, finds no ESP, and the view says how to reach it.
  const appPath = info.outputPath('firmware.bin');
  writeFileSync(appPath, Buffer.concat([Buffer.of(0xe9), Buffer.alloc(4095, 0x11)]));
  await page.getByTestId('firmware-esp-file-firmware.bin').setInputFiles(appPath);
  await page.getByTestId('firmware-esp-file-littlefs.bin').setInputFiles(fsPath);
  await page.getByTestId('firmware-flash').click();
  await expect(page.getByTestId('firmware-error')).toHaveAttribute('data-failure', 'no-bootloader', { timeout: 80_000 });
  expect(opened).toBeGreaterThan(0);
});
