import { readFileSync } from 'node:fs';
import { expect, it } from 'vitest';
import { ERRORS } from './errors';

it('matches protocol/errors.csv exactly', () => {
  const csv = readFileSync(new URL('../../../protocol/errors.csv', import.meta.url), 'utf8').trim().split('\n').slice(1);
  const table = csv.map((row) => {
    const [code, name, message] = row.split(',');
    return [name, { code: Number(code), message }];
  });
  expect(Object.entries(ERRORS)).toEqual(table);
});
