// Issue 29, items 1 and 2: never act on a machine that is busy. One rule decides which controls are
// open; each state of the simulated printer (idle, homing, running, paused, resuming, faulted,
// disconnected; cooling is walked in busy-machine-heat.spec.ts) is walked over every control that
// moves, fires or uploads, and a closed one says why.
import { expect, test, type Page } from '@playwright/test';
import { drawFilledRectangle } from './draw';
import { allClosed, expectControls, MACHINE_CONTROLS, type Expected } from './machine-controls';

async function open(page: Page, speed: number) {
  await page.setViewportSize({ width: 1440, height: 1000 });
  await page.goto(`/?simSpeed=${speed}`);
  await expect(page.getByTestId('connection')).toContainText('Connected to the simulated printer');
}

async function startTestPattern(page: Page, doseMs: string) {
  await page.getByLabel('Full dose').fill(doseMs);
  await page.getByTestId('strategy').selectOption('serpentine'); // stop and fire, stop by stop (the default, automatic, may scan)
  await page.getByRole('button', { name: 'Expose test pattern' }).click();
  await page.getByRole('dialog').getByRole('button', { name: /Expose (now|anyway)/ }).click();
  await expect(page.getByTestId('job-state')).toContainText(/running: stop [1-9]\d* of/, { timeout: 30_000 });
}

const every = (open: true | RegExp): Expected => Object.fromEntries(MACHINE_CONTROLS.map((c) => [c, open]));

test('each state of the machine opens only what it allows, and a closed control says why', async ({ page }, info) => {
  test.setTimeout(180_000);
  await open(page, 1);
  await drawFilledRectangle(page, [0.3, 0.3], [0.32, 0.32]);

  await expectControls(page, info, 'idle', { ...every(true), Pause: /no job is running/, Continue: /no job is paused/, Stop: /no job is running/ });

  // Running, then paused: the tester's case, where "Expose drawing" stayed open and sent G28 to the paused machine.
  await startTestPattern(page, '100'); // about 20 s of exposing at real time
  await expectControls(page, info, 'running', allClosed(/a job is running/, { Pause: true, Stop: true, Continue: /the job is running/ }));
  await page.getByRole('button', { name: 'Pause', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'paused');
  await expectControls(page, info, 'paused', allClosed(/a job is paused: continue or stop it first/, { Pause: /the job is paused/, Continue: true, Stop: true }));
  await expect(page.getByTestId('busy-note')).toContainText('Exposing and moving the head: not now, a job is paused');
  await page.getByRole('button', { name: 'Stop', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'aborted');

  // Homing: far from the switches, so that it lasts (the job homed the machine: Go asks nothing).
  await page.getByRole('tab', { name: 'Position' }).click();
  await page.getByTestId('goto-x').fill('190');
  await page.getByTestId('goto-y').fill('190');
  await page.getByRole('button', { name: 'Go', exact: true }).click();
  await expect(page.getByTestId('position')).toContainText('X 190.000 Y 190.000', { timeout: 30_000 });
  await page.getByRole('button', { name: 'Home', exact: true }).click();
  await expectControls(page, info, 'homing', allClosed(/the machine is homing/, { Home: /homing already/, Pause: /no job is running/, Continue: /no job is paused/, Stop: /no job is running/ }));
  await page.getByRole('tab', { name: 'Position' }).click();
  await expect(page.getByRole('button', { name: 'Home', exact: true })).toBeEnabled({ timeout: 30_000 });

  // Faulted: the printhead does not answer. The probe (on the printhead) is closed; exposing leads to the dry run, which says it.
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' }).check();
  await expect(page.getByTestId('faults')).toContainText('E30 printhead not responding', { timeout: 15_000 });
  const silent = /the printhead does not answer \(E30 printhead not responding\)/;
  await expectControls(page, info, 'faulted', { ...every(true), 'Probe deploy': silent, 'Probe test touch': silent, 'Probe the bed': silent, 'Leveling off': silent, Stop: /no job is running/ });
  await page.getByRole('tab', { name: 'Simulated printer' }).click();
  await page.getByRole('checkbox', { name: 'Printhead missing (no Nano answers)' }).uncheck();
  await expect(page.getByTestId('faults')).toHaveCount(0, { timeout: 15_000 }); // the app asks again, and it answers

  // Disconnected: nothing is open.
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await expect(page.getByTestId('connection')).toContainText('Not connected.');
  const { 'Apply and save': _unread, ...shown } = allClosed(/not connected/); // no settings to save before they are read
  await expectControls(page, info, 'disconnected', shown);
});

test('resuming says so at once, and closes every control until the job runs on', async ({ page }, info) => {
  test.setTimeout(180_000);
  await open(page, 1);
  await drawFilledRectangle(page, [0.3, 0.3], [0.32, 0.32]);
  await startTestPattern(page, '100');
  await page.getByRole('button', { name: 'Disconnect' }).click();
  await page.getByRole('button', { name: 'Connect', exact: true }).click(); // the Mega restarts, as over USB
  const offer = page.getByTestId('resume-offer');
  await expect(offer).toContainText(/test-pattern-1\.uvj: \d+ of \d+ stops are done/);
  // While offered, the interrupted job can be resumed or discarded, and nothing else is busy.
  await expect(offer.getByRole('button', { name: 'Resume' })).toBeEnabled();
  // Homing at 5 mm/s rather than 40 (the restarted Mega's RAM only): the resume's homing lasts the
  // tens of seconds that walking every control takes on a loaded machine, not one or two.
  const input = page.getByRole('textbox', { name: 'A line for the printer' });
  await input.fill('M850 speed.home 5');
  await input.press('Enter');
  await expect(page.getByTestId('console-log')).toContainText('M850 speed.home 5');

  await offer.getByRole('button', { name: 'Resume' }).click();
  // At once: the offer goes, and the page says what the machine is doing.
  const progress = page.getByTestId('resume-progress');
  await expect(progress).toContainText(/Resuming test-pattern-1\.uvj: homing… Then it runs on from stop \d+ of \d+\./, { timeout: 500 });
  await expect(offer).toHaveCount(0);
  await expect(page.getByTestId('job-state')).not.toContainText('No job.');
  await expect(page.getByTestId('job-state')).toContainText('Resuming: homing…');
  const resuming = /the interrupted job is resuming: the machine homes first/;
  await expectControls(page, info, 'resuming', allClosed(resuming));
  await expect(page.getByTestId('busy-note')).toContainText('not now, the interrupted job is resuming');

  // Then the job runs on, and the rule follows it.
  await expect(page.getByTestId('job-state')).toContainText(/running: stop \d+ of/, { timeout: 90_000 });
  await expect(progress).toHaveCount(0);
  await expect(page.getByRole('button', { name: 'Expose test pattern' })).toHaveAttribute('title', /a job is running/);
  await page.screenshot({ path: info.outputPath('resumed-running.png'), fullPage: true });
  await page.getByRole('button', { name: 'Stop', exact: true }).click();
  await expect(page.getByTestId('job-state')).toHaveAttribute('data-state', 'aborted');
});
