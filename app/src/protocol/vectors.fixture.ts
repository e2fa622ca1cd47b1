// Test-only: loads protocol/vectors/*.json and counts how many cases a suite checked.

import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { afterAll } from 'vitest';

// UV_VECTORS_DIR lets scripts/check-vectors-bind.py run the suite against a mutated copy.
const DIR = (process.env.UV_VECTORS_DIR ?? fileURLToPath(new URL('../../../protocol/vectors', import.meta.url))) + '/';

// eslint-disable-next-line @typescript-eslint/no-explicit-any
export function loadVectors(file: string): any {
  return JSON.parse(readFileSync(DIR + file, 'utf8'));
}

/** Call once per case; the total is printed when the file's tests end. */
export function vectorCounter(file: string): () => void {
  let n = 0;
  afterAll(() => console.log(`[vectors] ${file}: ${n} cases checked (TypeScript)`));
  return () => {
    n++;
  };
}

/** `[label, case]` rows for it.each, labelled by one field of each case. */
// eslint-disable-next-line @typescript-eslint/no-explicit-any
export function cases(list: any[], label: string): [string, any][] {
  return list.map((c) => [typeof c[label] === 'string' ? c[label] : JSON.stringify(c[label]), c]);
}
