import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['app/src/**/*.test.ts'],
    environment: 'node',
    // The simulated printer is the firmware's C++ as WebAssembly: compiled once per worker.
    setupFiles: ['app/src/sim/wasm/node-firmware.ts'],
  },
});
