import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['app/src/**/*.test.ts'],
    environment: 'node',
    // The simulated printer and the planner are the firmware's C++ as WebAssembly: compiled once per worker.
    setupFiles: ['app/src/sim/wasm/node-firmware.ts', 'app/src/planner/wasm/node-planner-wasm.ts'],
    // A time-out here catches a test that hangs; it measures nothing. The planner's property test and
    // the thermal forecast against the simulated printer take about 4 s on an idle 2-core machine, and
    // Vitest's 5 s default failed them on a loaded one.
    testTimeout: 30_000,
  },
});
