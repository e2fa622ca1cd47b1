import { svelte } from '@sveltejs/vite-plugin-svelte';
import { fileURLToPath } from 'node:url';
import { defineConfig, type Plugin } from 'vite';
import { bundleSize, formatBundleSize } from '../scripts/bundle-size';

const outDir = fileURLToPath(new URL('../dist/app', import.meta.url));

/** Prints the app's gzipped size, first load against its budget, after every build. */
const printSize: Plugin = {
  name: 'print-gzipped-size',
  apply: 'build',
  closeBundle() {
    console.log(`\nThe app, gzipped:\n${formatBundleSize(bundleSize(outDir))}`);
  },
};

export default defineConfig({
  root: fileURLToPath(new URL('.', import.meta.url)),
  plugins: [svelte(), printSize],
  build: {
    outDir,
    emptyOutDir: true,
  },
  worker: { format: 'es' },
  server: { port: 5173 },
  preview: { port: 4173 },
});
