// The studio's keys wherever the focus is, not only on the canvas: a tool's letter, and undo and redo.
// A click on a tool button leaves the focus on it, and Ctrl+Z there did nothing (issue 29, item 14).

export type Shortcut<T extends string> = { kind: 'tool'; tool: T } | { kind: 'undo' } | { kind: 'redo' } | null;

export interface Keypress {
  key: string;
  shift: boolean;
  /** Ctrl, or ⌘ on a Mac. */
  mod: boolean;
  alt: boolean;
}

/** What has its own keys: a field that takes text (its own undo, its letters) or a list that picks by letter. */
export interface Focus {
  tagName: string;
  type?: string;
  isContentEditable?: boolean;
  /** In an open dialog (the question before an exposure): the drawing behind it is not what the keys act on. */
  inDialog?: boolean;
}

const NOT_TEXT = new Set(['checkbox', 'radio', 'range', 'button', 'submit', 'reset', 'color', 'file', 'image']);

/** Whether the focused element takes the keys itself: a text field, a number field, a list, editable text. */
export function takesKeys(focus: Focus | null): boolean {
  if (!focus) return false;
  const tag = focus.tagName.toUpperCase();
  if (tag === 'TEXTAREA' || tag === 'SELECT' || focus.isContentEditable) return true;
  return tag === 'INPUT' && !NOT_TEXT.has((focus.type ?? 'text').toLowerCase());
}

/**
 * The studio's shortcut for a key pressed with `focus` (null: the page itself): Ctrl+Z undo,
 * Ctrl+Shift+Z or Ctrl+Y redo, a tool's letter (`tools`, lower case; Shift+R is `shiftR`).
 */
export function shortcutOf<T extends string>(k: Keypress, focus: Focus | null, tools: Record<string, T>, shiftR: T): Shortcut<T> {
  if (takesKeys(focus) || focus?.inDialog || k.alt) return null;
  const key = k.key.toLowerCase();
  if (k.mod) {
    if (key === 'z') return { kind: k.shift ? 'redo' : 'undo' };
    if (key === 'y') return { kind: 'redo' };
    return null;
  }
  const tool = k.shift && key === 'r' ? shiftR : tools[key];
  return tool ? { kind: 'tool', tool } : null;
}
