// The Gerber library must load on demand: nothing outside app/src/pcb may import it statically (import() and `import type` are fine),
// but the work worker (app/src/work/, its own file started with new Worker), which reads boards off the page's thread.
import { readdirSync, readFileSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';
import { describe, expect, it } from 'vitest';

const SRC = join(import.meta.dirname, '..');
const WORKER = join(SRC, 'work');

function sources(dir: string): string[] {
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) return path === import.meta.dirname || path === WORKER ? [] : sources(path);
    return /\.(ts|svelte)$/.test(name) && !name.endsWith('.test.ts') ? [path] : [];
  });
}

describe('the Gerber import stays out of the first load', () => {
  it('is imported statically by nothing outside app/src/pcb', () => {
    const offenders = sources(SRC).filter((path) => {
      const text = readFileSync(path, 'utf8');
      return /^\s*import\s+(?!type\b)[^;]*?from\s+['"][^'"]*\/pcb(?:\/[^'"]*)?['"]/m.test(text) || /^\s*export\s+[^;]*?from\s+['"][^'"]*\/pcb(?:\/[^'"]*)?['"]/m.test(text);
    });
    expect(offenders.map((p) => relative(SRC, p))).toEqual([]);
  });
});
