// The lines that count as homing, the probe's work or changing settings, and those that do not.
import { describe, expect, it } from 'vitest';
import { lineWork } from './line-work';

describe('lineWork', () => {
  it.each([
    ['G28', 'homing'],
    ['g28 X', 'homing'],
    ['G29 X3 Y3', 'probing'],
    ['g30', 'probing'],
    ['M401', 'probing'],
    ['M402', 'probing'],
    ['M280 P0 S160', 'probing'],
    ['M850 speed.travel 120', 'configuring'],
    ['M500', 'configuring'],
    ['M501', 'configuring'],
    ['M502', 'configuring'],
  ] as const)('%s is %s', (line, work) => expect(lineWork(line)).toBe(work));

  it.each(['M850 speed.travel', 'M503', 'G280', 'G1 X10', 'M4010', 'G290', 'M105', 'M5000'])('%s is neither', (line) => expect(lineWork(line)).toBeNull());
});
