// Test-only: the app built for GitHub Pages twice, as two deployments (npm run build:pages, the command the
// workflow's pages job runs), once per test worker. Each build carries its own VITE_APP_VERSION, so the
// second is a new version: a new entry chunk, new chunk names, a new service worker.
import { test as base } from '@playwright/test';
import { execFileSync } from 'node:child_process';
import { join } from 'node:path';

const ROOT = join(import.meta.dirname, '..');

export interface PagesBuilds {
  /** The first deployment's files, and the version it shows. */
  a: { dir: string; version: string };
  /** The next deployment's. */
  b: { dir: string; version: string };
}

function build(name: string): { dir: string; version: string } {
  const dir = join(ROOT, 'dist', `pages-${name}`);
  const version = `deploy-${name}`;
  try {
    execFileSync('npm', ['run', '--silent', 'build:pages', '--', '--outDir', dir, '--emptyOutDir', '--logLevel', 'error'], {
      cwd: ROOT,
      stdio: ['ignore', 'pipe', 'pipe'],
      env: { ...process.env, VITE_APP_VERSION: version },
    });
  } catch (e) {
    const { stdout, stderr } = e as { stdout?: Buffer; stderr?: Buffer };
    throw new Error(`npm run build:pages for ${version} failed:\n${stdout ?? ''}${stderr ?? ''}`);
  }
  return { dir, version };
}

export const test = base.extend<object, { builds: PagesBuilds }>({
  builds: [async ({}, use) => use({ a: build('a'), b: build('b') }), { scope: 'worker', timeout: 120_000 }],
});
export { expect } from '@playwright/test';
