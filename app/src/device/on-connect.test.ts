// The text dialect's client loads on connect, after the first screen (issue 28 §3; docs/app.md "Size"):
// only what itself loads on connect (the links, the `dialect` chunk in app/vite.config.ts) or runs in
// the simulated printer imports it statically; `import type` and import() are fine.
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';
import { describe, expect, it } from 'vitest';

const SRC = join(import.meta.dirname, '..');
const ON_CONNECT = /\/(dialect-client|dialect-link|dialect-reply|line-splitter|dialect-frame|sim-link)['"]/;
const LOADED_ON_CONNECT = ['device/chosen-links.ts', 'device/dialect-client.ts', 'device/dialect-link.ts', 'device/esp-link.ts', 'device/sim-link.ts'];
/** The simulated printer's side of the link, in its worker; and the upload's size, counted in the work worker's dry run (work/dry-run-work.ts). */
const SIMULATOR = /^(sim\/|job\/upload-time\.ts$)/;

function sources(dir: string): string[] {
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) return sources(path);
    return /\.(ts|svelte)$/.test(name) && !name.endsWith('.test.ts') ? [path] : [];
  });
}

function importsStatically(text: string): boolean {
  return text.split('\n').some((line) => /^\s*(import|export)\s+(?!type\b)[^;]*?from\s+['"]/.test(line) && ON_CONNECT.test(line));
}

describe('the text dialect stays out of the first load', () => {
  it('is imported statically only by what loads on connect, or by the simulated printer', () => {
    const offenders = sources(SRC)
      .map((path) => relative(SRC, path))
      .filter((file) => !LOADED_ON_CONNECT.includes(file) && !SIMULATOR.test(file) && importsStatically(readFileSync(join(SRC, file), 'utf8')));
    expect(offenders).toEqual([]);
  });

  it('finds a static import where there is one', () => {
    expect(importsStatically("import { DialectLink } from './dialect-link';")).toBe(true);
    expect(importsStatically("import { parseReply, type Reply } from '../protocol/dialect-reply';")).toBe(true);
    expect(importsStatically("import type { Reply } from '../protocol/dialect-reply';")).toBe(false);
    expect(importsStatically("  return (await import('./sim-link')).simLink();")).toBe(false);
  });
});
