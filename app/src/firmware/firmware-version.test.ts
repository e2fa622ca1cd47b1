import { describe, expect, it } from 'vitest';
import { AVR_BOARDS } from './chips';
import { askVersion, explainAnswer, type LineLink } from './firmware-version';

const mega = AVR_BOARDS.find((b) => b.id === 'mega')!;

/** A just-flashed Mega: `start`, then each M115 answered with `answer` lines. */
function megaSaying(atStart: string[], answer: string[]): LineLink {
  const lines = ['start', ...atStart];
  return {
    async write(bytes) {
      if (new TextDecoder().decode(bytes) === 'M115\n') lines.push(...answer);
    },
    async readLine(ms) {
      if (lines.length) return lines.shift()!;
      await new Promise((r) => setTimeout(r, Math.min(ms, 5)));
      return null;
    },
  };
}

describe('after flashing, what the firmware answered', () => {
  it('is its version when it says it', async () => {
    const answer = await askVersion(megaSaying([], ['FIRMWARE_NAME:UVExposure 1.2.3 (Mega) PROTOCOL_VERSION:1', 'ok']), mega);
    expect(answer).toEqual({ version: 'UVExposure 1.2.3 (Mega)', also: [] });
  });

  it('is "halted: E13" when the stop button reads pressed, not "silent"', async () => {
    const answer = await askVersion(megaSaying(['echo:stop button: halted, send M999'], ['Error:E13 machine halted: send M999']), mega);
    expect(answer).toMatchObject({ summary: 'halted: E13 — release the stop button, then send M999 (or reset the board)' });
  });

  it('is the line with an error code otherwise', () => {
    expect(explainAnswer(['hello', 'echo:E10 unknown command: M115']).summary).toBe('it answered "echo:E10 unknown command: M115"');
    expect(explainAnswer(['something else']).summary).toBe('it answered "something else"');
  });
});
