import { svelte } from '@sveltejs/vite-plugin-svelte';
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { defineConfig, type Plugin } from 'vite';
import { bundleSize, formatBundleSize } from '../scripts/bundle-size.ts';
import { compileHint } from './compile-hint.ts';
import { serviceWorker } from './pwa.ts';

/**
 * What loads after the first screen goes to a chunk by its folder (app/src/<folder>/), so a new file
 * lands in its folder's chunk. The `first` group comes before them and keeps whatever the entry
 * imports statically in the entry's file, whatever its folder. A chunk may import an earlier one but
 * never a later one, which would then load with it: what both use (ui/, machine/) goes in the earlier.
 * - `dialect`, on connect, just after the first screen: the link and its dialect, the dashboards and
 *   the console (mounted a few tasks after the first screen), and project/, whose file format restore
 *   and autosave need (the material test rides along). As files of their own, the link's helpers, the
 *   job's encoder and the project file each took a 4 KB block of the ESP's flash.
 * - `panels`, when first opened: the dashboards' tabs, the settings, the preview, the question before
 *   a job, the delivered dose, the studio's object and import panels, the work worker's clients.
 * Other folders (firmware/) get rolldown's own chunk for each import().
 */
const FOLDER_CHUNKS: Record<string, string> = {
  console: 'dialect',
  dashboards: 'dialect',
  device: 'dialect',
  machine: 'dialect',
  project: 'dialect',
  protocol: 'dialect',
  ui: 'dialect',
  job: 'panels',
  planner: 'panels',
  preview: 'panels',
  settings: 'panels',
  studio: 'panels',
  work: 'panels',
};

/**
 * Files whose folder mixes what loads at different times, and their chunk. null keeps their import()'s
 * own chunk: as a group, the chosen links took a file beside it.
 */
const NOT_BY_FOLDER: [RegExp, string | null][] = [
  // uPlot's chart loads when the page is idle after its first paint.
  [/\/dashboards\/(thermal-chart|chart-time)\.ts$/, null],
  // The dashboards' tabs load when opened.
  [/\/dashboards\/((Position|Probe|Mesh|Link)Dashboard\.svelte|mesh-(figures|image)\.ts)$/, 'panels'],
  // The Wi-Fi hub's and USB's links load when that device is chosen.
  [/\/device\/(chosen-links|esp-link|esp-post|serial-transport)\.ts$/, null],
  // The studio mounts a task after the first screen, its panels later.
  [/\/studio\/((Studio|EditorCanvas|ImportPanel)\.svelte|shortcuts\.ts|canvas\/|objects\/import-accept\.ts)/, null],
  // The Firmware tab's entry, which the dashboards import: alone, a file of 190 B.
  [/\/firmware\/firmware-view(-absent)?\.ts$/, 'dialect'],
  // The project file reads the halftones' names.
  [/\/studio\/image\/halftones\.ts$/, 'dialect'],
];

/**
 * The Web Serial polyfill (USB over WebUSB where there is no Web Serial): a file of its own took a
 * 4 KB block of the ESP's flash for 1.8 KB, so it rides in the dialect's file, loaded on connect.
 */
const SERIAL_POLYFILL = /\/node_modules\/web-serial-polyfill\//;
/** Espressif's esptool-js with its stub flashers, one file: the Firmware view loads it to flash an ESP. */
const ESPTOOL = /\/node_modules\/(esptool-js|pako|atob-lite)\//;

/** The chunk of a module that the first screen does not import; null leaves it to rolldown. */
function chunkOf(id: string): string | null {
  if (SERIAL_POLYFILL.test(id)) return 'dialect';
  if (ESPTOOL.test(id)) return 'esptool';
  const named = NOT_BY_FOLDER.find(([test]) => test.test(id));
  if (named) return named[1];
  const folder = /\/app\/src\/([^/]+)\//.exec(id)?.[1];
  return (folder && FOLDER_CHUNKS[folder]) || null;
}

/**
 * The first screen's views: App.svelte, the components it imports statically, and theirs. Every other
 * view loads on demand and brings its styles in its chunk (Svelte injects them when it is first shown),
 * so the one stylesheet holds only the first screen's and no further file goes to the flash.
 */
function firstScreenViews(file = fileURLToPath(new URL('src/App.svelte', import.meta.url)), seen = new Set<string>()): Set<string> {
  seen.add(file);
  for (const [, spec] of readFileSync(file, 'utf8').matchAll(/^\s*import\s+\w+\s+from\s+['"](\.[^'"]+\.svelte)['"]/gm)) {
    const path = resolve(dirname(file), spec);
    if (!seen.has(path)) firstScreenViews(path, seen);
  }
  return seen;
}
const FIRST_SCREEN = firstScreenViews();

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
  plugins: [svelte({ configFile: false, dynamicCompileOptions: ({ filename }) => (FIRST_SCREEN.has(filename) ? undefined : { css: 'injected' }) }), serviceWorker(fileURLToPath(new URL('service-worker.js', import.meta.url))), compileHint(), printSize()],
  build: {
    outDir,
    emptyOutDir: true,
    // Every browser the app runs in preloads modules itself (Chromium since 66, Firefox 115, Safari
    // 17); without that, a preload is only a hint missed. Vite's polyfill would be first-load code no
    // browser of ours runs.
    modulePreload: { polyfill: false },
    // Few files: the ESP's LittleFS gives each file whole 4 KB blocks. One stylesheet (the other views'
    // styles ride in their chunks: FIRST_SCREEN), and what loads later in a few chunks by folder
    // (chunkOf); uPlot's chart, the studio and the chosen links keep their import()'s own. Without a
    // group, a chunk loaded on demand can split the first load into several files: `first` keeps all
    // the entry imports statically in the entry's file (alone, protocol/nano.ts's 229 B took a block).
    cssCodeSplit: false,
    rolldownOptions: { output: { codeSplitting: { includeDependenciesRecursively: false, groups: [{ name: 'first', tags: ['$initial'] }, { name: chunkOf, debugName: 'by folder' }] } } },
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
