// Issue 29, item 12: the thermal chart's time axis read "now, 20 min … 100 min" at first, then
// "-3 s, -2 s, -2 s, -1 s, -1 s, now" under "minutes before now". From the first sample on, each
// tick is a different time, in the unit it says, and the window grows with the history.
import { expect, test, type Locator } from '@playwright/test';

/** The ticks the chart drew on its canvas, as it words them. */
const ticks = async (chart: Locator) => ((await chart.getAttribute('data-time-ticks')) ?? '').split(', ');
const samples = async (chart: Locator) => Number(await chart.getAttribute('data-samples'));

test('the time axis says the truth from the first second', async ({ page }, info) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=1');
  const chart = page.getByTestId('thermal-chart');
  await expect(chart.locator('canvas')).toHaveCount(1);
  await expect(chart).toHaveAttribute('data-time-caption', 'time before now'); // drawn on the canvas, as the ticks are
  // Before and just after the first reports: a minute's window.
  await expect.poll(() => ticks(chart)).toEqual(['-1 min', '-45 s', '-30 s', '-15 s', 'now']);
  await chart.screenshot({ path: info.outputPath('axis-first.png') });
  await expect.poll(() => samples(chart), { timeout: 15_000 }).toBeGreaterThanOrEqual(4);
  expect(await ticks(chart)).toEqual(['-1 min', '-45 s', '-30 s', '-15 s', 'now']);
  await chart.screenshot({ path: info.outputPath('axis-seconds.png') });
});

// The speed raised on the simulated printer's panel: its heartbeat follows (sim-transport.ts
// setSimulatorSpeed), or the printer stalls between beats and the chart's samples come in bursts.
// The Thermal tab chosen again makes its chart at once: when it waited for idle time the page never had
// at 20x, the chart came back 5 s later, past the 2 minute window (the fresh-clone run of b43f59e).
test('the time axis widens through 2, 5, 10 and 20 minutes as the history grows', async ({ page }, info) => {
  test.setTimeout(120_000);
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto('/?simSpeed=1');
  const chart = page.getByTestId('thermal-chart');
  await expect.poll(() => samples(chart), { timeout: 15_000 }).toBeGreaterThanOrEqual(4);

  // Faster: the window widens through 2, 5, 10 and 20 minutes as the history grows, its ticks always distinct.
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByLabel('Speed (× real time)').fill('20');
  await page.getByRole('tab', { name: 'Thermal' }).click();
  const windows = [
    ['-2 min', '-1 min 30 s', '-1 min', '-30 s', 'now'],
    ['-5 min', '-4 min', '-3 min', '-2 min', '-1 min', 'now'],
    ['-10 min', '-8 min', '-6 min', '-4 min', '-2 min', 'now'],
    ['-20 min', '-15 min', '-10 min', '-5 min', 'now'],
  ];
  for (const want of windows) {
    await expect.poll(() => ticks(chart), { timeout: 60_000, intervals: [250] }).toEqual(want);
    await chart.screenshot({ path: info.outputPath(`axis${want[0].replace(' ', '-')}.png`) });
  }
});
