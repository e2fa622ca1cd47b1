// Test-only: opens the app on each transport, with a simulated printer behind it running `speed` times real time.
import type { Page } from '@playwright/test';
import { startEspHost } from './esp-host';
import type { SimOptions } from '../app/src/sim/sim-printer';
import { installFakeSerial, type FakeSerial } from './fake-serial';
import { NodeSim } from './node-sim';

export type TransportName = 'simulated' | 'web serial' | 'esp';
/**
 * `esp` is the ESP's own C++ core on the host (build/host/esp_host), over real HTTP and WebSocket,
 * serving the app from its flash image, in front of the whole simulated Mega: the hub has no second,
 * TypeScript imitation to drift from it.
 */
export const TRANSPORTS: TransportName[] = ['simulated', 'web serial', 'esp'];

export interface Opened {
  /** The printer behind the transport, when the test can reach it (not inside the page's worker). */
  sim: NodeSim | null;
  fake: FakeSerial | null;
  close(): void;
}

export async function openApp(page: Page, transport: TransportName, speed = 40, options: SimOptions = {}): Promise<Opened> {
  if (transport === 'simulated') {
    await page.goto(`/?simSpeed=${speed}`);
    return { sim: null, fake: null, close() {} };
  }
  if (transport === 'esp') {
    const host = await startEspHost(speed);
    await page.goto(host.url); // served by the hub itself, so the app finds it by its GET /status
    return { sim: null, fake: null, close: () => host.stop() };
  }
  const sim = new NodeSim(options, speed);
  const fake = await installFakeSerial(page, (f) => {
    sim.attach((bytes) => void f.push(bytes));
    return sim;
  });
  await page.goto('/');
  await page.getByTestId('connection').and(page.locator('[data-state="connected"]')).waitFor();
  await page.getByTestId('device-kind').selectOption('serial');
  await page.getByRole('button', { name: 'Connect', exact: true }).click();
  return { sim, fake, close: () => sim.stop() };
}
