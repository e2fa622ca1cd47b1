// Build step for the installable, offline app: writes sw.js from service-worker.js with the list of
// every file the build made (the simulated printer's worker and the chart included; not the ESP
// flasher's) and a version hash of them, so the app works with no network and a new build replaces
// the old cache. The ESP's image (--mode esp) gets neither the worker nor the manifest: it is served
// from http://192.168.4.1, not a secure context, where no service worker runs and nothing installs.
import { createHash } from 'node:crypto';
import { readFileSync } from 'node:fs';
import { minify, type Plugin } from 'vite';

/**
 * Chunks left out of the cache: Espressif's flasher (108 KB gzipped) loads only when someone flashes
 * an ESP, which needs the board's images from the network anyway. Cached, every first visit would
 * download it in the background, and its name would sit in sw.js, which the first load counts.
 */
const NOT_CACHED = /^assets\/(esptool|esp-flash)-/;

export function serviceWorker(source: string): Plugin {
  let esp = false;
  return {
    name: 'service-worker',
    apply: 'build',
    // After Vite's own plugins: the single stylesheet (cssCodeSplit off) is emitted in their generateBundle.
    enforce: 'post',
    configResolved(config) {
      esp = config.mode === 'esp';
    },
    transformIndexHtml(html) {
      return esp ? html.replace(/\s*<link rel="manifest"[^>]*>/, '') : html;
    },
    async generateBundle(_options, bundle) {
      if (esp) return;
      // Relative to the worker's scope, which is the folder the app is served from.
      const files = ['index.html', ...Object.keys(bundle).filter((f) => f !== 'index.html' && !NOT_CACHED.test(f)), 'manifest.webmanifest', 'icon.svg'].sort();
      const hash = createHash('sha256');
      for (const f of Object.values(bundle)) hash.update(f.type === 'chunk' ? f.code : typeof f.source === 'string' ? f.source : Buffer.from(f.source));
      const code = readFileSync(source, 'utf8')
        .replace('self.__PRECACHE__', JSON.stringify(files))
        .replace('self.__VERSION__', JSON.stringify(hash.digest('hex').slice(0, 12)));
      // Minified: every first visit downloads it, and the first load counts it (its comments are for
      // this repository, not for every visitor).
      const min = await minify('sw.js', code, { compress: true, mangle: true });
      if (min.errors.length) this.error(`sw.js: ${min.errors.map((e) => e.message).join('; ')}`);
      this.emitFile({ type: 'asset', fileName: 'sw.js', source: min.code });
    },
  };
}
