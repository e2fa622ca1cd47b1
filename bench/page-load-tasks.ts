// B4's page-load row alone, N times (issue 40): each load of the built app from its first script (a
// buffered longtask observer) until connected and the thermal chart drawn, and a second more, with
// every long task as [start, duration] ms and where the first mount fell. One B4 run gives one load;
// this gives a spread at the machine's load of the moment, in a few seconds a load.
//   npm run build && npx tsx bench/page-load-tasks.ts [N=5]
import { chromium } from '@playwright/test';
import { loadavg } from 'node:os';
import { serve } from './editor.bench';

const n = Number(process.argv[2] ?? 5);
const { url, close } = await serve();
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM_PATH ?? '/usr/bin/chromium', args: ['--no-sandbox'] });
const longest: number[] = [];
try {
  for (let i = 0; i < n; i++) {
    const page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
    await page.addInitScript('window.__name = (f) => f');
    await page.addInitScript(() => {
      const w = window as unknown as { __lt: number[][]; __mount?: number };
      w.__lt = [];
      new PerformanceObserver((l) => l.getEntries().forEach((e) => w.__lt.push([Math.round(e.startTime), Math.round(e.duration)]))).observe({ type: 'longtask', buffered: true });
      new MutationObserver((_, o) => {
        if (!document.querySelector('header')) return;
        w.__mount = Math.round(performance.now());
        o.disconnect();
      }).observe(document, { childList: true, subtree: true });
    });
    const load = loadavg()[0];
    await page.goto(url);
    await page.getByTestId('connection').and(page.locator('[data-state="connected"]')).waitFor({ timeout: 30_000 });
    await page.getByTestId('thermal-chart').locator('canvas').waitFor({ timeout: 30_000 });
    await page.waitForTimeout(1000);
    const { tasks, mount } = await page.evaluate(() => {
      const w = window as unknown as { __lt: number[][]; __mount?: number };
      return { tasks: w.__lt, mount: w.__mount };
    });
    const max = Math.max(0, ...tasks.map((t) => t[1]));
    longest.push(max);
    console.log(`load ${load.toFixed(1)}: longest ${max} ms   long tasks ${JSON.stringify(tasks)}   first mount at ${mount} ms`);
    await page.context().close();
  }
} finally {
  await browser.close();
  close();
}
console.log(`longest task of each load, sorted: ${longest.sort((a, b) => a - b).join(' ')} ms (budget 50)`);
