// Builds the app for the ESP's flash: vite's output gzipped into firmware/esp/data/www, the
// folder PlatformIO's `uploadfs` turns into the LittleFS image. Each file is kept only as
// <name>.gz; the ESP serves it with Content-Encoding: gzip and an ETag from its gzip trailer.
// Prints each file and the total against the flash the ESP keeps for the app (protocol/esp.md).
import { execFileSync } from 'node:child_process';
import { mkdirSync, readdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { gzipSync } from 'node:zlib';

const root = new URL('..', import.meta.url).pathname;
const dist = join(root, 'dist', 'esp-app');
const www = join(root, 'firmware', 'esp', 'data', 'www');
// LittleFS gives every file whole 4 KB blocks. The smaller layout, an ESP32's default partitions,
// has 0x160000 B of LittleFS: 352 blocks. One 1.2 MB job body takes 293, the superblock pair and a
// metadata pair per directory (/, /www, /www/assets) take 6, and 2 more are kept for
// copy-on-write while the body is replaced: 51 are left for the app.
const BLOCK = 4096;
const APP_BLOCKS = 51;

execFileSync('npx', ['vite', 'build', '--config', 'app/vite.config.ts', '--mode', 'esp', '--outDir', dist, '--emptyOutDir'], { cwd: root, stdio: 'inherit' });
// The hub serves http://192.168.4.1, not a secure context: no service worker runs there and nothing
// installs, so the web manifest (public/, copied by Vite) stays off the flash, as the worker does
// (app/pwa.ts emits none in --mode esp, and leaves the manifest's link out of index.html).
rmSync(join(dist, 'manifest.webmanifest'), { force: true });
inlineIntoPage(dist);

/**
 * The stylesheet (1.5 KB gzipped) and the icon (0.2 KB) each took a block of their own: they go into
 * index.html instead, which the page needs first anyway, so the first load makes two requests fewer.
 * The page's tags are Vite's own output (app/index.html); anything else is an error, not a guess.
 */
function inlineIntoPage(dir) {
  const page = join(dir, 'index.html');
  let html = readFileSync(page, 'utf8');
  const sheet = /<link rel="stylesheet" crossorigin href="\/(assets\/[\w.-]+\.css)">/.exec(html);
  const icon = /<link rel="icon" href="\/icon\.svg" type="image\/svg\+xml" \/>/.exec(html);
  if (!sheet || !icon) throw new Error(`[esp fs] index.html has no ${sheet ? 'icon' : 'stylesheet'} link to take in`);
  const css = readFileSync(join(dir, sheet[1]), 'utf8');
  if (css.includes('</style')) throw new Error('[esp fs] the stylesheet holds </style>');
  const svg = readFileSync(join(dir, 'icon.svg'), 'utf8');
  html = html.replace(sheet[0], () => `<style>${css}</style>`).replace(icon[0], () => `<link rel="icon" href="data:image/svg+xml,${encodeURIComponent(svg)}" type="image/svg+xml" />`);
  writeFileSync(page, html);
  rmSync(join(dir, sheet[1]));
  rmSync(join(dir, 'icon.svg'));
}

rmSync(www, { recursive: true, force: true });
let total = 0, blocks = 0;
function walk(dir) {
  for (const name of readdirSync(dir)) {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) {
      walk(path);
      continue;
    }
    const rel = relative(dist, path);
    const gz = gzipSync(readFileSync(path), { level: 9 });
    mkdirSync(join(www, rel, '..'), { recursive: true });
    writeFileSync(join(www, `${rel}.gz`), gz);
    total += gz.length;
    blocks += Math.max(1, Math.ceil(gz.length / BLOCK));
    console.log(`  /www/${rel}.gz  ${gz.length} B`);
  }
}
walk(dist);
console.log(`[esp fs] app for LittleFS: ${total} B gzipped in ${blocks} blocks of 4 KB (budget ${APP_BLOCKS} blocks, ${(APP_BLOCKS * BLOCK) / 1024} KB) in firmware/esp/data/www`);
if (blocks > APP_BLOCKS) {
  console.error('[esp fs] the app is over the flash budget');
  process.exit(1);
}
