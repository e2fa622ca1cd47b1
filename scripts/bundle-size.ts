// The app's size, gzipped as the ESP serves it: what the first load fetches (index.html and what it
// names), what loads on demand (the thermal chart with uPlot, the Web Serial polyfill), and the
// simulated printer's worker, which only the simulated device loads. Printed by the build and the bench
// (B2), or alone after a build: npx tsx scripts/bundle-size.ts [dist/app].
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { gzipSync } from 'node:zlib';

export const FIRST_LOAD_BUDGET = 60 * 1024;

const gz = (path: string) => gzipSync(readFileSync(path), { level: 9 }).length;

export interface Sized {
  file: string;
  gzip: number;
}

export interface BundleSize {
  first: Sized[];
  onDemand: Sized[];
  simulator: Sized[];
  firstLoad: number;
  onDemandTotal: number;
  simulatorTotal: number;
  total: number;
}

export function bundleSize(dist: string): BundleSize {
  const html = readFileSync(join(dist, 'index.html'), 'utf8');
  // Any base: "/assets/…" (the default), "./assets/…" (--base ./, as Pages gets it), "/REPO/assets/…".
  const named = new Set([...html.matchAll(/(?:src|href)="(?:[^"]*\/)?(assets\/[^"/]+)"/g)].map((m) => m[1]));
  const files: Sized[] = readdirSync(join(dist, 'assets')).map((f) => ({ file: `assets/${f}`, gzip: gz(join(dist, 'assets', f)) }));
  // index.html, what it names, and the files beside it: the manifest, the icon, the service worker.
  // Not the firmware images (firmware/), which only the Firmware view fetches.
  const root: Sized[] = readdirSync(dist).filter((f) => f !== 'assets' && f !== 'firmware').map((f) => ({ file: f, gzip: gz(join(dist, f)) }));
  const first = [...root, ...files.filter((f) => named.has(f.file))];
  const simulator = files.filter((f) => !named.has(f.file) && /sim-worker/.test(f.file));
  const onDemand = files.filter((f) => !named.has(f.file) && !/sim-worker/.test(f.file));
  const sum = (l: Sized[]) => l.reduce((n, f) => n + f.gzip, 0);
  return { first, onDemand, simulator, firstLoad: sum(first), onDemandTotal: sum(onDemand), simulatorTotal: sum(simulator), total: sum(files) + sum(root) };
}

const kb = (n: number) => `${(n / 1024).toFixed(1)} KB`;

/** The first load against its budget, and what is left of it: "(budget 60 KB, 4.2 KB left)". */
export function headroom(firstLoad: number): string {
  const left = FIRST_LOAD_BUDGET - firstLoad;
  return `(budget ${FIRST_LOAD_BUDGET / 1024} KB, ${left >= 0 ? `${kb(left)} left` : `${kb(-left)} OVER BUDGET`})`;
}

export function formatBundleSize(s: BundleSize): string {
  return [
    `first load   ${kb(s.firstLoad).padStart(8)}  ${headroom(s.firstLoad)}`,
    `on demand    ${kb(s.onDemandTotal).padStart(8)}  ${s.onDemand.map((f) => `${f.file.replace(/^assets\//, '').replace(/-[\w-]{8}\./, '.')} ${kb(f.gzip)}`).join(', ')}`,
    `simulator    ${kb(s.simulatorTotal).padStart(8)}  (the built-in simulated printer's worker)`,
    `whole app    ${kb(s.total).padStart(8)}`,
  ].join('\n');
}

if (process.argv[1] && import.meta.url === pathToFileURL(process.argv[1]).href) console.log(formatBundleSize(bundleSize(process.argv[2] ?? 'dist/app')));
