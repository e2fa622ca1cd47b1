import { describe, expect, it } from 'vitest';
import { shortcutOf, takesKeys, type Keypress } from './shortcuts';

const TOOLS = { b: 'brush', r: 'rect', v: 'select' } as const;
type Tool = (typeof TOOLS)[keyof typeof TOOLS] | 'rect-filled';
const press = (key: string, more: Partial<Keypress> = {}): Keypress => ({ key, shift: false, mod: false, alt: false, ...more });
const at = (k: Keypress, focus: Parameters<typeof shortcutOf>[1] = null) => shortcutOf<Tool>(k, focus, TOOLS, 'rect-filled');
const button = { tagName: 'BUTTON' };

describe('the studio\'s keys', () => {
  it('undoes and redoes with the focus on a tool button, as on the page (issue 29, item 14)', () => {
    expect(at(press('z', { mod: true }), button)).toEqual({ kind: 'undo' });
    expect(at(press('Z', { mod: true, shift: true }), button)).toEqual({ kind: 'redo' });
    expect(at(press('y', { mod: true }), button)).toEqual({ kind: 'redo' });
    expect(at(press('z', { mod: true }))).toEqual({ kind: 'undo' });
    expect(at(press('z', { mod: true }), { tagName: 'INPUT', type: 'checkbox' })).toEqual({ kind: 'undo' });
  });

  it('leaves fields that take text their own keys and undo', () => {
    for (const field of [{ tagName: 'INPUT' }, { tagName: 'input', type: 'number' }, { tagName: 'TEXTAREA' }, { tagName: 'SELECT' }, { tagName: 'DIV', isContentEditable: true }]) {
      expect(takesKeys(field)).toBe(true);
      expect(at(press('z', { mod: true }), field)).toBeNull();
      expect(at(press('b'), field)).toBeNull();
    }
    expect(takesKeys({ tagName: 'INPUT', type: 'range' })).toBe(false);
    // The question before an exposure holds the job it asks about: Ctrl+Z there does not change the drawing behind it.
    expect(at(press('z', { mod: true }), { tagName: 'BUTTON', inDialog: true })).toBeNull();
    expect(takesKeys(button)).toBe(false);
  });

  it('picks tools by letter, Shift+R the filled rectangle, and nothing with Ctrl or Alt', () => {
    expect(at(press('b'), button)).toEqual({ kind: 'tool', tool: 'brush' });
    expect(at(press('R', { shift: true }))).toEqual({ kind: 'tool', tool: 'rect-filled' });
    expect(at(press('r'))).toEqual({ kind: 'tool', tool: 'rect' });
    expect(at(press('b', { mod: true }))).toBeNull();
    expect(at(press('b', { alt: true }))).toBeNull();
    expect(at(press('q'))).toBeNull();
  });
});
