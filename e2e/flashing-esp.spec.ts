// The Firmware view's ESP path: the published ESP image (firmware and LittleFS) from the manifest, the
// board's DIP switches, and the hand-off to Espressif's esptool-js over the fake Web Serial. No ESP can
// run here: the port's far end is silent, so the library's connect must fail and the view say what to do.
import { createHash } from 'node:crypto';
import { expect, test } from '@playwright/test';
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
