import { describe, expect, it } from 'vitest';
import { parseReply, type Reply } from '../protocol/dialect-reply';
import { configOf, interruptedOf, levelingOf } from './printer-replies';

const replies = (...lines: string[]) => lines.map((l) => parseReply(l)).filter((r): r is Reply => r !== null);

describe('configOf', () => {
  it('reads every M850 line of M503, values with commas and fractions as written', () => {
    expect(configOf(replies('M850 bed.x 204.8', 'M850 led.offset.1 0,1', 'echo:something else', 'ok'))).toEqual({
      'bed.x': '204.8',
      'led.offset.1': '0,1',
    });
  });
});

describe('interruptedOf', () => {
  it('reads the checkpoint M1000 S reports', () => {
    expect(interruptedOf(replies('JOB:interrupted file=drawing-1.uvj stop=41/120', 'ok'))).toEqual({ file: 'drawing-1.uvj', done: 41, stops: 120 });
  });

  it('is null without one, or for a line it cannot read', () => {
    expect(interruptedOf(replies('JOB:idle', 'ok'))).toBeNull();
    expect(interruptedOf(replies('JOB:interrupted file=x stop=garbage'))).toBeNull();
  });
});

describe('levelingOf', () => {
  it('reads bare M420\'s answer, and is null when there is none', () => {
    expect(levelingOf(replies('echo:leveling on', 'ok'))).toBe(true);
    expect(levelingOf(replies('echo:leveling off', 'ok'))).toBe(false);
    expect(levelingOf(replies('ok'))).toBeNull();
  });
});
