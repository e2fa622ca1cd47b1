import { readFileSync } from 'node:fs';
import { expect, it } from 'vitest';
import { ERRORS, errorClass, formatError } from './errors';

it('matches protocol/errors.csv exactly', () => {
  const csv = readFileSync(new URL('../../../protocol/errors.csv', import.meta.url), 'utf8').trim().split('\n').slice(1);
  const table = csv.map((row) => {
    const [code, name, message] = row.split(',');
    return [name, { code: Number(code), message }];
  });
  expect(Object.entries(ERRORS)).toEqual(table);
});

it('classes every code as errors.csv does', () => {
  const csv = readFileSync(new URL('../../../protocol/errors.csv', import.meta.url), 'utf8').trim().split('\n').slice(1);
  for (const row of csv) {
    const [code, , , , cls] = row.split(',');
    expect([code, errorClass(Number(code))]).toEqual([code, cls]);
  }
});

it('answers refusals as echo and faults as Error, as Marlin does', () => {
  expect(formatError(14, 'X')).toBe('echo:E14 axis not homed: X');
  expect(formatError(31)).toBe('Error:E31 over-temperature');
  expect(formatError(2)).toBe('Error:E2 checksum mismatch');
});
