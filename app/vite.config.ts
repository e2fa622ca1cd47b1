import { svelte } from '@sveltejs/vite-plugin-svelte';
import { fileURLToPath } from 'node:url';
import { defineConfig, type Plugin } from 'vite';
import { bundleSize, formatBundleSize } from '../scripts/bundle-size.ts';
import { compileHint } from './compile-hint.ts';
import { serviceWorker } from './pwa.ts';

/** What loads only when a panel is first opened: grouped into one chunk. */
const ON_DEMAND_PANELS = /\/(PositionDashboard|ProbeDashboard|MeshDashboard|LinkDashboard|mesh-image|Settings|setting-groups|setting-docs|Lamp|PreviewPanel|exposure-preview|preview-colours|MaterialTest|material-test|ObjectPanel|BoardPanel|board-object|fonts|Panel|ImportFile|import-artwork|artwork|svg-artwork|svg-size|density|picture|decode|clipping|dry-run|plan|job-header|time-model|adjust|gray|dither|ConfirmDialog|hms|thermal-forecast|pacing|mesh|mesh-figures|scan-words|work-client|check-job|job-transfer|remote-artwork|settings-table|DeliveredDose|dose-plan|dose-map|dose-colours|dose-batch)\.(svelte|ts)$/;

/**
 * The text dialect's client and the simulated printer's link on it, loaded on connect, just after the
 * first screen (device/links.ts); with them the dashboards and the console, mounted a few tasks after
 * the first screen (App.svelte, ui/Soon.svelte: mounted with it, the page load's longest task). The
 * link's helpers and the job's encoder, which the panels, the links and saving share with it, ride here
 * too: as files of their own (109 and 613 B gzipped) each took a 4 KB block of the ESP's flash.
 */
const ON_DEMAND_DIALECT = /\/(sim-link|dialect-link|dialect-client|dialect-reply|line-splitter|dialect-frame)\.ts$|\/(Dashboards|ThermalDashboard|Console)\.svelte$|\/(thermal-watch|intl-warm|sensor-colours|head-thermal|firmware-view|firmware-view-absent)\.ts$|\/(device\/link|protocol\/job-encode|protocol\/job-runs)\.ts$/;
/**
 * The Web Serial polyfill (USB over WebUSB where there is no Web Serial): a file of its own took a
 * 4 KB block of the ESP's flash for 1.8 KB, so it rides in the dialect's file, loaded on connect.
 */
const SERIAL_POLYFILL = /\/node_modules\/web-serial-polyfill\//;
/** Espressif's esptool-js with its stub flashers, one file: the Firmware view loads it to flash an ESP. */
const ESPTOOL = /\/node_modules\/(esptool-js|pako|atob-lite)\//;

/**
 * Views that load on demand bring their styles in their own chunk (Svelte injects them when first
 * shown), so the one stylesheet holds only the first screen's and no further file goes to the flash.
 */
const LAZY_VIEW = new RegExp(`${ON_DEMAND_PANELS.source}|/(SimulatorPanel|FirmwarePanel|Dashboards|ThermalDashboard|Console)\\.svelte$`);

/** What saving, opening or running something needs: the project file, the job's encoding, the test pattern, framing. */
const ON_DEMAND_FILES = /\/(project-file|cells-codec|halftones|job-types|job-encode|crc32|test-pattern|framing)\.ts$/;

/**
 * The Gerber parser and plotter are Node transform streams that app/src/pcb/tracespace.ts drives by
 * hand: small stand-ins for readable-stream and string_decoder keep Node's stream polyfills (half the
 * Gerber chunk) out of the build. Why each is enough is in its file. Their lodash helpers (padStart,
 * padEnd, fill, isFunction, isFinite from before ES2015 was everywhere) give way to the language's
 * own: 7 KB of the work worker, which the ESP's flash counts in whole blocks.
 */
export const STREAM_SHIMS = [
  { find: /^readable-stream$/, replacement: fileURLToPath(new URL('src/pcb/stream-shim.ts', import.meta.url)) },
  { find: /^string_decoder$/, replacement: fileURLToPath(new URL('src/pcb/string-decoder-shim.ts', import.meta.url)) },
  ...['padstart', 'padend', 'fill', 'isfunction', 'isfinite'].map((name) => ({
    find: new RegExp(`^lodash\\.${name}$`),
    replacement: fileURLToPath(new URL(`src/pcb/lodash-shims/${name}.cjs`, import.meta.url)),
  })),
];

const outDir = fileURLToPath(new URL('../dist/app', import.meta.url));

/** Prints the app's gzipped size, first load against its budget, after every build, wherever it went. */
function printSize(): Plugin {
  let dir = outDir;
  return {
    name: 'print-gzipped-size',
    apply: 'build',
    configResolved(config) {
      dir = config.build.outDir;
    },
    closeBundle() {
      console.log(`\nThe app, gzipped:\n${formatBundleSize(bundleSize(dir))}`);
    },
  };
}

export default defineConfig(({ mode }) => ({
  root: fileURLToPath(new URL('.', import.meta.url)),
  plugins: [svelte({ configFile: false, dynamicCompileOptions: ({ filename }) => (LAZY_VIEW.test(filename) ? { css: 'injected' } : undefined) }), serviceWorker(fileURLToPath(new URL('service-worker.js', import.meta.url))), compileHint(), printSize()],
  build: {
    outDir,
    emptyOutDir: true,
    // Every browser the app runs in preloads modules itself (Chromium since 66, Firefox 115, Safari
    // 17); without that, a preload is only a hint missed. Vite's polyfill would be first-load code no
    // browser of ours runs.
    modulePreload: { polyfill: false },
    // Few files: the ESP's LittleFS gives each file whole 4 KB blocks. One stylesheet (the lazy views'
    // styles ride in their chunks: LAZY_VIEW), the panels that load on demand in one chunk, what saving
    // and running need in another (the dashboards, the console and the Web Serial polyfill ride with
    // the dialect); uPlot's chart stays apart. Without a group, a chunk loaded on demand can split the
    // first load into several files: `first` keeps all the entry imports statically in the entry's
    // file (alone, protocol/nano.ts's 229 B took a block). The links the user picks (device/chosen-links.ts)
    // are one chunk without a group: as a group they took a file beside the import()'s own.
    cssCodeSplit: false,
    rolldownOptions: { output: { codeSplitting: { includeDependenciesRecursively: false, groups: [{ name: 'first', tags: ['$initial'] }, { name: 'panels', test: ON_DEMAND_PANELS }, { name: 'files', test: ON_DEMAND_FILES }, { name: 'dialect', test: new RegExp(`${ON_DEMAND_DIALECT.source}|${SERIAL_POLYFILL.source}`) }, { name: 'esptool', test: ESPTOOL }] } } },
  },
  worker: { format: 'es' },
  server: { port: 5173 },
  // The dev server's dependency scan starts from index.html and does not follow `new Worker(...)`:
  // without the workers as entries, the Gerber packages the work worker imports are found only when
  // it first starts, and Vite reloads the page under the user (a drawing lost, Undo gone).
  optimizeDeps: { entries: ['index.html', 'src/work/worker.ts', 'src/sim/sim-worker.ts'] },
  preview: { port: 4173 },
  // The Gerber libraries' Node streams give way to stand-ins (STREAM_SHIMS); the ESP's flash image
  // (scripts/build-esp-fs.mjs) also leaves the simulated printer out.
  resolve: {
    alias: [
      ...STREAM_SHIMS,
      ...(mode === 'esp'
        ? [
            { find: /^\.\/sim-transport$/, replacement: fileURLToPath(new URL('src/device/sim-absent.ts', import.meta.url)) },
            // No Firmware view in the hub's own image (app/src/firmware/firmware-view.ts).
            { find: /^\.\.\/firmware\/firmware-view$/, replacement: fileURLToPath(new URL('src/firmware/firmware-view-absent.ts', import.meta.url)) },
          ]
        : []),
    ],
  },
}));
