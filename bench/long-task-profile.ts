// What runs in the page's long tasks (issue 40): a Chrome CPU profile of the built app per case (page
// load, small import, whole-bed rectangle, 36 MP PNG, busy Gerber, preview, dry run), cut into runs of
// busy samples over 40 ms, each with its functions by self and total time. Built with source maps
// (`npx vite build --config app/vite.config.ts --sourcemap`), it names the source lines; without, the
// bundle's positions. Wall-clock samples: on a loaded machine every run is longer.
//   npx tsx bench/long-task-profile.ts [load small rect png gerber preview dryrun]
import { chromium, type Page } from '@playwright/test';
import { existsSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { SourceMapConsumer } from 'source-map-js';
import { busyBoard } from '../app/src/pcb/test-boards';
import { drawFilledRectangle } from '../e2e/draw';
import { greyPng, watchLongTasks } from '../e2e/long-tasks';
import { serve } from './editor.bench';

const ASSETS = join(import.meta.dirname, '..', 'dist', 'app', 'assets');
const maps = new Map<string, SourceMapConsumer | null>();
/** A bundle position as its source line, where the build has a source map. */
function sourceOf(file: string, line: number, column: number): string | null {
  if (!maps.has(file)) maps.set(file, existsSync(join(ASSETS, `${file}.map`)) ? new SourceMapConsumer(JSON.parse(readFileSync(join(ASSETS, `${file}.map`), 'utf8'))) : null);
  const o = maps.get(file)?.originalPositionFor({ line, column });
  return o?.source ? `${o.source.replace(/^(\.\.\/)+/, '').replace(/^.*node_modules\//, '')}:${o.line}` : null;
}

const IMPORT = /^Import artwork \(SVG, PNG, JPG, BMP, GIF\)/;
type Node = { id: number; callFrame: { functionName: string; url: string; lineNumber: number; columnNumber: number }; children?: number[]; positionTicks?: { line: number; ticks: number }[] };
function analyse(prof: { nodes: Node[]; samples: number[]; timeDeltas: number[]; startTime: number }, label: string) {
  const byId = new Map(prof.nodes.map((n) => [n.id, n]));
  const parent = new Map<number, number>();
  for (const n of prof.nodes) for (const c of n.children ?? []) parent.set(c, n.id);
  const idle = (id: number) => ['(idle)', '(program)', '(garbage collector)'].includes(byId.get(id)!.callFrame.functionName) && byId.get(id)!.callFrame.functionName !== '(garbage collector)';
  let t = 0; const times: number[] = [];
  for (const d of prof.timeDeltas) { t += d; times.push(t / 1000); }
  // runs of non-idle samples
  let start = -1; const runs: [number, number][] = [];
  for (let i = 0; i < prof.samples.length; i++) {
    const busy = !idle(prof.samples[i]);
    if (busy && start < 0) start = i;
    if ((!busy || i === prof.samples.length - 1) && start >= 0) { runs.push([start, i]); start = -1; }
  }
  const fmt = (id: number) => {
    const f = byId.get(id)!.callFrame, file = f.url.split('/').pop() ?? '';
    return `${f.functionName || '(anon)'} ${(file && sourceOf(file, f.lineNumber + 1, f.columnNumber)) ?? `${file}:${f.lineNumber + 1}:${f.columnNumber}`}`;
  };
  for (const [a, b] of runs) {
    const ms = times[b] - times[a];
    if (ms < 40) continue;
    const self = new Map<string, number>(); const incl = new Map<string, number>();
    for (let i = a; i < b; i++) {
      const dt = times[i + 1] - times[i];
      self.set(fmt(prof.samples[i]), (self.get(fmt(prof.samples[i])) ?? 0) + dt);
      const seen = new Set<string>();
      for (let id: number | undefined = prof.samples[i]; id !== undefined; id = parent.get(id)) { const k = fmt(id); if (!seen.has(k)) { seen.add(k); incl.set(k, (incl.get(k) ?? 0) + dt); } }
    }
    // The lines the samples fell on (positionTicks: the bundle's line; its column unknown, so the line's first mapping)
    const lines = new Map<string, number>();
    const inRun = new Set(prof.samples.slice(a, b));
    for (const id of inRun) {
      const n = byId.get(id)!, file = n.callFrame.url.split('/').pop() ?? '';
      for (const t of n.positionTicks ?? []) {
        const k = `${n.callFrame.functionName || '(anon)'} ${(file && sourceOf(file, t.line, n.callFrame.lineNumber + 1 === t.line ? n.callFrame.columnNumber : 0)) ?? `${file}:${t.line}`}`;
        lines.set(k, (lines.get(k) ?? 0) + t.ticks);
      }
    }
    console.log(`\n[${label}] busy run ${ms.toFixed(0)} ms at ${times[a].toFixed(0)} ms`);
    if (lines.size) console.log('  lines (ticks over the whole profile): ' + [...lines].sort((x, y) => y[1] - x[1]).slice(0, 6).map(([k, v]) => `${v} ${k}`).join('\n        '));
    console.log('  self: ' + [...self].sort((x, y) => y[1] - x[1]).slice(0, 10).map(([k, v]) => `${v.toFixed(0)} ${k}`).join('\n        '));
    console.log('  incl: ' + [...incl].sort((x, y) => y[1] - x[1]).slice(0, Number(process.env.TOPN ?? 25)).map(([k, v]) => `${v.toFixed(0)} ${k}`).join('\n        '));
  }
}
const which = process.argv.slice(2);
const { url, close } = await serve();
const browser = await chromium.launch({ executablePath: '/usr/bin/chromium', args: ['--no-sandbox'] });
const dir = mkdtempSync(join(tmpdir(), 'uv-profile-'));
writeFileSync(`${dir}/big.png`, greyPng(6000, 6000, 1000));
writeFileSync(`${dir}/small.png`, greyPng(400, 300, 300));
writeFileSync(`${dir}/busy-F_Cu.gbr`, busyBoard());
async function scenario(name: string, body: (p: Page) => Promise<void>, beforeLoad = false, setup?: (p: Page) => Promise<void>) {
  if (which.length && !which.includes(name)) return;
  const page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
  await page.addInitScript('window.__name = (f) => f');
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('Profiler.enable');
  await cdp.send('Profiler.setSamplingInterval', { interval: 200 });
  if (beforeLoad) {
    await page.addInitScript(() => { const w = window as any; w.__lt = []; new PerformanceObserver((l) => { for (const e of l.getEntries()) w.__lt.push([Math.round(e.startTime), Math.round(e.duration)]); }).observe({ type: 'longtask', buffered: true } as any); });
    await cdp.send('Profiler.start');
    await page.goto(url);
    await page.getByTestId('connection').and(page.locator('[data-state="connected"]')).waitFor({ timeout: 30_000 });
    await page.waitForTimeout(3000);
    const { profile } = await cdp.send('Profiler.stop');
    console.log(`\n=== ${name}: longtasks`, JSON.stringify(await page.evaluate(() => (window as any).__lt)));
    analyse(profile as any, name);
  } else {
    await page.goto(url);
    await page.getByTestId('connection').and(page.locator('[data-state="connected"]')).waitFor({ timeout: 30_000 });
    await page.waitForTimeout(3000);
    if (setup) { await setup(page); await page.waitForTimeout(2500); }
    const watch = await watchLongTasks(page);
    await cdp.send('Profiler.start');
    await body(page);
    const { profile } = await cdp.send('Profiler.stop');
    console.log(`\n=== ${name}: longtasks`, JSON.stringify(await watch.stop()));
    analyse(profile as any, name);
  }
  await page.context().close();
}
await scenario('load', async () => {}, true);
await scenario('small', async (page) => {
  await page.getByLabel(IMPORT).setInputFiles(`${dir}/small.png`);
  await page.getByRole('region', { name: 'Selected object' }).getByText('small.png').waitFor({ timeout: 60_000 });
  await page.waitForTimeout(1500);
});
await scenario('rect', async (page) => { await drawFilledRectangle(page, [0.001, 0.001], [0.999, 0.999]); await page.waitForTimeout(2000); });
await scenario('png', async (page) => {
  await page.getByLabel(IMPORT).setInputFiles(`${dir}/big.png`);
  await page.getByRole('region', { name: 'Selected object' }).getByText('big.png').waitFor({ timeout: 120_000 });
  await page.waitForTimeout(3000);
});
await scenario('gerber', async (page) => {
  await page.getByLabel(IMPORT).setInputFiles(`${dir}/busy-F_Cu.gbr`);
  await page.getByRole('region', { name: 'Selected object' }).getByText('busy').first().waitFor({ timeout: 120_000 });
  await page.waitForTimeout(1000);
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await page.getByRole('dialog', { name: 'Expose the drawing?' }).getByText(/of exposing/).waitFor({ timeout: 120_000 });
  await page.waitForTimeout(1000);
});
await scenario('preview', async (page) => {
  await page.getByTestId('view-preview').click();
  await page.getByTestId('preview-summary').getByText(/about/).waitFor({ timeout: 120_000 });
  await page.waitForTimeout(500);
}, false, (page) => drawFilledRectangle(page, [0.001, 0.001], [0.999, 0.999]));
await scenario('dryrun', async (page) => {
  await page.getByRole('button', { name: 'Expose drawing' }).click();
  await page.getByRole('dialog', { name: 'Expose the drawing?' }).getByText(/of exposing/).waitFor({ timeout: 120_000 });
}, false, (page) => drawFilledRectangle(page, [0.001, 0.001], [0.999, 0.999]));
await browser.close(); close();
