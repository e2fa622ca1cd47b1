import { svelte } from '@sveltejs/vite-plugin-svelte';
import { fileURLToPath } from 'node:url';
import { defineConfig, type Plugin } from 'vite';
import { bundleSize, formatBundleSize } from '../scripts/bundle-size.ts';
import { serviceWorker } from './pwa.ts';

/** What loads only when a panel is first opened: grouped into one chunk. */
const ON_DEMAND_PANELS = /\/(PositionDashboard|ProbeDashboard|MeshDashboard|LinkDashboard|mesh-image|Settings|setting-groups|setting-docs|Lamp|PreviewPanel|exposure-preview|plan-client|preview-colours|MaterialTest|material-test|ObjectPanel|BoardPanel|board-object|fonts|Panel|ImportFile|import-artwork|artwork|svg-artwork|svg-size|density|picture|decode|clipping|dry-run|planner|job-header|time-model|adjust|gray|dither|ConfirmDialog|hms|thermal-forecast|pacing)\.(svelte|ts)|\/CONFIG\.md\?raw$/; // CONFIG.md: the settings' words (setting-docs.ts)

/** What saving, opening or running something needs: the project file, the job's encoding, the test pattern, framing. */
const ON_DEMAND_FILES = /\/(project-file|cells-codec|halftones|job-types|job-encode|crc32|test-pattern|framing)\.ts$/;

/** The Wi-Fi hub's link and the USB transport, loaded when that device is chosen. */
const ON_DEMAND_LINKS = /\/(esp-link|serial-transport)\.ts$/;

/**
 * The Gerber parser and plotter are Node transform streams that app/src/pcb/tracespace.ts drives by
 * hand: small stand-ins for readable-stream and string_decoder keep Node's stream polyfills (half the
 * Gerber chunk) out of the build. Why each is enough is in its file.
 */
export const STREAM_SHIMS = [
  { find: /^readable-stream$/, replacement: fileURLToPath(new URL('src/pcb/stream-shim.ts', import.meta.url)) },
  { find: /^string_decoder$/, replacement: fileURLToPath(new URL('src/pcb/string-decoder-shim.ts', import.meta.url)) },
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
  plugins: [svelte({ configFile: false }), serviceWorker(fileURLToPath(new URL('service-worker.js', import.meta.url))), printSize()],
  build: {
    outDir,
    emptyOutDir: true,
    // Few files: the ESP's LittleFS gives each file whole 4 KB blocks. One stylesheet, and the
    // panels that load on demand in one chunk; uPlot's chart and the serial polyfill stay apart.
    cssCodeSplit: false,
    rolldownOptions: { output: { codeSplitting: { includeDependenciesRecursively: false, groups: [{ name: 'panels', test: ON_DEMAND_PANELS }, { name: 'files', test: ON_DEMAND_FILES }, { name: 'links', test: ON_DEMAND_LINKS }] } } },
  },
  worker: { format: 'es' },
  server: { port: 5173 },
  preview: { port: 4173 },
  // The Gerber libraries' Node streams give way to stand-ins (STREAM_SHIMS); the ESP's flash image
  // (scripts/build-esp-fs.mjs) also leaves the simulated printer out.
  resolve: {
    alias: [...STREAM_SHIMS, ...(mode === 'esp' ? [{ find: /^\.\/sim-transport$/, replacement: fileURLToPath(new URL('src/device/sim-absent.ts', import.meta.url)) }] : [])],
  },
}));
