import { describe, expect, it } from 'vitest';
import { typeKey } from './typing';

describe('typing into a placed text', () => {
  it('replaces the placeholder with the first character, then appends, Space included', () => {
    let t = 'Text', fresh = true;
    for (const k of ['H', 'i', ' ', 'P', 'C', 'B']) {
      const r = typeKey(t, k, { fresh })!;
      t = r.text;
      fresh = false;
    }
    expect(t).toBe('Hi PCB');
  });
  it('deletes with Backspace, breaks a line with Shift+Enter, ends with Enter or Escape', () => {
    expect(typeKey('ab', 'Backspace', { fresh: false })).toEqual({ text: 'a', done: false });
    expect(typeKey('ab', 'Enter', { fresh: false, shift: true })).toEqual({ text: 'ab\n', done: false });
    expect(typeKey('ab', 'Enter', { fresh: false })).toEqual({ text: 'ab', done: true });
    expect(typeKey('ab', 'Escape', { fresh: false })).toEqual({ text: 'ab', done: true });
  });
  it('leaves keys that are not typing to the canvas', () => {
    expect(typeKey('ab', 'ArrowLeft', { fresh: false })).toBeNull();
    expect(typeKey('ab', 'z', { fresh: false, mod: true })).toBeNull();
  });
});
