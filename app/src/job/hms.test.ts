import { expect, it } from 'vitest';
import { hms } from './hms';

it('shows µs as h:mm:ss', () => {
  expect(hms(207e6)).toBe('0:03:27');
  expect(hms(9894e6)).toBe('2:44:54');
  expect(hms(0)).toBe('0:00:00');
});
