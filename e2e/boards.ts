// Test-only: a board's files picked for import, and its settings read as a person reads them (roles and labels).
import { expect, type Page } from '@playwright/test';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

export const PCB = join(import.meta.dirname, 'fixtures/pcb');
export const IMPORT_LABEL = /^Import artwork \(SVG, PNG, JPG, BMP, GIF\)/;

/** The studio at this size, connected to the simulated printer. */
export async function openStudio(page: Page, size = { width: 1440, height: 900 }) {
  await page.setViewportSize(size);
  await page.goto('/?simSpeed=40');
  await expect(page.getByTestId('connection')).toHaveAttribute('data-state', 'connected', { timeout: 20_000 });
}

/** Files from e2e/fixtures/pcb/<dir>, picked together, each under its own name or the one given. */
export async function importBoard(page: Page, dir: string, files: (string | [string, string])[]) {
  await page.getByLabel(IMPORT_LABEL).setInputFiles(
    files.map((f) => {
      const [from, name] = typeof f === 'string' ? [f, f] : f;
      return { name, mimeType: 'application/octet-stream', buffer: readFileSync(join(PCB, dir, from)) };
    }),
  );
}

export const selected = (page: Page) => page.getByRole('region', { name: 'Selected object' });
export const kindOf = (page: Page, file: string) => selected(page).getByLabel(`Layer of ${file}`, { exact: true });
export const exposeOf = (page: Page, file: string) => selected(page).getByLabel(`Expose ${file}`, { exact: true });

/** The selected object's size in mm, as its panel shows it. */
export async function sizeShown(page: Page): Promise<{ w: number; h: number }> {
  const field = (name: RegExp) => selected(page).getByRole('spinbutton', { name });
  return { w: Number(await field(/^W\b/).inputValue()), h: Number(await field(/^H\b/).inputValue()) };
}
