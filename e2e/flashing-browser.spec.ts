// Browsers without Web Serial: the app says why USB is greyed out, and what WebUSB cannot reach.
import { expect, test } from '@playwright/test';
import { IMAGES } from './bootloader-rig';

test('without Web Serial or WebUSB (Firefox, Safari), USB is greyed out with its reason, and flashing says it once', async ({ page }) => {
  await page.addInitScript(() => {
    delete (Navigator.prototype as unknown as Record<string, unknown>).serial;
    delete (Navigator.prototype as unknown as Record<string, unknown>).usb;
  });
  await page.goto('/');
  await expect(page.getByTestId('serial-note')).toHaveText(/no Web Serial: Firefox and Safari.*Use Chrome or Edge on a desktop computer\.$/);
  await expect(page.locator('[data-testid="device-kind"] option[value="serial"]')).toBeDisabled();
  await page.getByTestId('tab-firmware').click();
  await expect(page.getByTestId('firmware-serial-note')).toContainText('Use Chrome or Edge on a desktop computer');
  await page.getByTestId('firmware-board').selectOption('nano');
  await page.getByTestId('firmware-source').selectOption('file');
  await page.getByTestId('firmware-file').setInputFiles(IMAGES.nano);
  await page.getByTestId('firmware-flash').click();
  const error = page.getByTestId('firmware-error');
  await expect(error).toHaveAttribute('data-failure', 'browser');
  // One cause, one message: not run together with the advice for a port in use.
  await expect(error).toHaveText(/^This browser has no Web Serial.*desktop computer\.$/);
});

test('with WebUSB only (Chrome on Android), the app says CH340 and FTDI boards never appear', async ({ page }) => {
  await page.addInitScript(() => {
    delete (Navigator.prototype as unknown as Record<string, unknown>).serial;
    if (!('usb' in navigator)) Object.defineProperty(Navigator.prototype, 'usb', { value: {}, configurable: true });
  });
  await page.goto('/');
  await expect(page.getByTestId('serial-note')).toContainText('A Nano with a CH340 or FTDI chip never appears');
  await expect(page.locator('[data-testid="device-kind"] option[value="serial"]')).toBeEnabled();
});
