// End-to-end tests in Debian's headless Chromium against the built app (build && preview).
import { defineConfig } from '@playwright/test';

// E2E_PORT: another checkout on the same machine may already serve its own build on 4173.
const PORT = Number(process.env.E2E_PORT ?? 4274);

export default defineConfig({
  testDir: 'e2e',
  outputDir: 'test-results',
  timeout: 30_000,
  fullyParallel: false,
  workers: 1,
  reporter: [['list']],
  use: {
    baseURL: `http://127.0.0.1:${PORT}`,
    screenshot: 'on',
    trace: 'retain-on-failure',
    launchOptions: {
      executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium',
      args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
        '--disable-component-update', '--disable-sync'],
    },
  },
  webServer: {
    // The ESP's image too: the hub's own C++ on the host (e2e/esp-host.ts) serves it, as the ESP does.
    command: `npm run build && npm run build:esp && npm run preview -- --port ${PORT} --strictPort`,
    url: `http://127.0.0.1:${PORT}`,
    reuseExistingServer: !process.env.CI,
    timeout: 120_000,
  },
});
