// Test-only: every control that moves, fires or uploads, found as a person finds it (its tab, its
// role and name), and checked open, or closed with its reason in its tooltip (issue 29, item 1).
import { expect, type Page, type TestInfo } from '@playwright/test';

type Tab = 'Position' | 'Probe & mesh' | 'Settings' | null;

/** Each control: the tab it is on (null: the job panel or the studio, always shown) and its button's name. */
const CONTROLS: Record<string, { tab: Tab; name: string }> = {
  'Expose drawing': { tab: null, name: 'Expose drawing' },
  'Expose test pattern': { tab: null, name: 'Expose test pattern' },
  Frame: { tab: null, name: 'Frame' },
  Pause: { tab: null, name: 'Pause' },
  Continue: { tab: null, name: 'Continue' },
  Stop: { tab: null, name: 'Stop' },
  Home: { tab: 'Position', name: 'Home' },
  'Jog X+': { tab: 'Position', name: 'X+' },
  'Go to': { tab: 'Position', name: 'Go' },
  'Release motors': { tab: 'Position', name: 'Release motors' },
  'Quick self-test': { tab: 'Position', name: 'Quick self-test' },
  'Probe deploy': { tab: 'Probe & mesh', name: 'Deploy' },
  'Probe test touch': { tab: 'Probe & mesh', name: 'Test touch' },
  'Probe the bed': { tab: 'Probe & mesh', name: 'Probe the bed' },
  'Leveling off': { tab: 'Probe & mesh', name: 'Leveling off' },
  'Apply and save': { tab: 'Settings', name: 'Apply and save' },
};
export type Control = keyof typeof CONTROLS;
export const MACHINE_CONTROLS = Object.keys(CONTROLS).filter((c) => !['Pause', 'Continue', 'Stop'].includes(c));

/** What each control should be: open (true), or closed with a tooltip that says why (matching the RegExp). */
export type Expected = Partial<Record<Control, true | RegExp>>;

/** Every machine control closed for `why`, and the job's three as given. */
export function allClosed(why: RegExp, job: Expected = {}): Expected {
  return { ...Object.fromEntries(MACHINE_CONTROLS.map((c) => [c, why])), Pause: why, Continue: why, Stop: why, ...job };
}

/** Checks each control on its tab, then keeps a screenshot of the page in this state. */
export async function expectControls(page: Page, info: TestInfo, state: string, expected: Expected): Promise<void> {
  const tabs: Tab[] = [null, 'Position', 'Probe & mesh', 'Settings'];
  for (const tab of tabs) {
    const here = Object.entries(expected).filter(([c]) => CONTROLS[c].tab === tab);
    if (!here.length) continue;
    if (tab) await page.getByRole('tab', { name: tab }).click();
    for (const [control, want] of here) {
      const scope = tab ? page.getByRole('tabpanel') : control === 'Expose drawing' ? page : page.getByRole('region', { name: 'Job' });
      const button = scope.getByRole('button', { name: CONTROLS[control].name, exact: true });
      if (want === true) await expect(button, `${state}: ${control} open`).toBeEnabled();
      else if (want) {
        await expect(button, `${state}: ${control} closed`).toBeDisabled();
        await expect(button, `${state}: ${control} says why`).toHaveAttribute('title', want);
      }
    }
    await page.screenshot({ path: info.outputPath(`${state}-${tab ?? 'job'}.png`.replace(/[ &]+/g, '-')), fullPage: true });
  }
  if (expected.Pause !== undefined) await page.getByRole('tab', { name: 'Thermal' }).click();
}
