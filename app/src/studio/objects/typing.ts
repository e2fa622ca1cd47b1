// Typing into a text object on the canvas, as a person expects after clicking with the Text tool:
// what each key does to the text. Pure, so it is tested apart from the canvas.

export type TypingResult = { text: string; done: boolean } | null;

/**
 * The text after `key` (KeyboardEvent.key). `fresh`: nothing typed yet, so the first character
 * replaces the placeholder. Enter or Escape ends typing (Shift+Enter is a new line); a key that
 * is not typing (arrows, shortcuts with Ctrl) gives null and is left to the canvas.
 */
export function typeKey(text: string, key: string, opts: { fresh: boolean; shift?: boolean; mod?: boolean }): TypingResult {
  if (opts.mod) return null;
  if (key === 'Escape' || (key === 'Enter' && !opts.shift)) return { text, done: true };
  if (key === 'Enter') return { text: `${opts.fresh ? '' : text}\n`, done: false };
  if (key === 'Backspace') return { text: opts.fresh ? '' : [...text].slice(0, -1).join(''), done: false };
  if ([...key].length === 1) return { text: opts.fresh ? key : text + key, done: false };
  return null;
}
