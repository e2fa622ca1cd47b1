// The first vertical slice: the app on the simulated printer, and the same app over Web Serial.
import { expect, test } from '@playwright/test';
import { NodeSim } from './node-sim';
import { installFakeSerial } from './fake-serial';

test('starts on the simulated printer and shows its firmware and six temperatures', async ({ page }, info) => {
  await page.goto('/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await expect(page.getByTestId('firmware')).toHaveText('UVExposure 0.1.0 (Mega)');
  for (let i = 0; i < 6; i++) await expect(page.getByTestId(`temp-${i}`)).toHaveText(/^-?\d+\.\d °C$/);
  await page.screenshot({ path: info.outputPath('simulated.png'), fullPage: true });
});

test('connects over Web Serial to a port answered in Node as the Mega would', async ({ page }, info) => {
  const mega = new NodeSim({ ambientDeciC: [215, 216, 217, 218, 219, -12] });
  const fake = await installFakeSerial(page, (f) => {
    mega.attach((bytes) => void f.push(bytes));
    return mega;
  });
  await page.goto('/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('device-kind').selectOption('serial');
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('firmware')).toHaveText('UVExposure 0.1.0 (Mega)');
  await expect(page.getByTestId('connection')).toHaveText('Connected over USB.');
  const expected = ['21.5', '21.6', '21.7', '21.8', '21.9', '-1.2'];
  for (let i = 0; i < 6; i++) await expect(page.getByTestId(`temp-${i}`)).toHaveText(`${expected[i]} °C`);
  // The app framed every command with a line number and checksum, as protocol/mega.md asks.
  expect(fake.written()).toMatch(/^N0 M110 N0\*\d+#[0-9a-f]{4}\nN1 M115\*\d+#[0-9a-f]{4}\nN2 M105\*\d+#[0-9a-f]{4}\nN3 M155 S1\*\d+#[0-9a-f]{4}\n/);
  await page.screenshot({ path: info.outputPath('web-serial.png'), fullPage: true });
  mega.stop();
});

test('a dismissed port picker is not an error', async ({ page }) => {
  await installFakeSerial(page, () => ({ receive() {} }), 'dismiss');
  await page.goto('/');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected');
  await page.getByTestId('device-kind').selectOption('serial');
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'idle');
  await expect(page.getByTestId('connection')).toHaveText('Not connected.');
});
