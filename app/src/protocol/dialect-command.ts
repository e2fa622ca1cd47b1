// Parses a dialect line body into a command word and fixed-point parameters (protocol/mega.md §1).

export type Command =
  | { word: string; params: Record<string, number | null> }
  | { word: string; text: string };

export type CommandResult = { ok: true; command: Command } | { ok: false; error: 10 | 11 };

/** Commands whose argument is the rest of the line. */
const FILE_COMMANDS = new Set(['M23', 'M28', 'M30', 'M32']);
const TEXT_COMMANDS = new Set(['M850', 'M117']);
// An optional leading `/` names the card's root, its only folder (OctoPrint writes it); `~` is in DOS short names.
const FILE_NAME = /^\/?([A-Za-z0-9_.~-]{1,31})$/;
export const MAX_MILLI = 2_000_000_000;

/** `-?digits[.digits]` to thousandths, rounded half away from zero; null if malformed or too big. */
export function parseMilli(s: string): number | null {
  const m = /^(-?)([0-9]+)(?:\.([0-9]+))?$/.exec(s);
  if (!m) return null;
  const intPart = m[2].replace(/^0+(?=.)/, '');
  if (intPart.length > 7) return null;
  const frac = (m[3] ?? '').padEnd(4, '0');
  let v = Number(intPart) * 1000 + Number(frac.slice(0, 3));
  if (Number(frac[3]) >= 5) v += 1;
  if (v > MAX_MILLI) return null;
  return m[1] && v !== 0 ? -v : v;
}

/** Thousandths as a decimal with exactly three fraction digits, as reports print mm. */
export function formatMilli(v: number): string {
  const a = Math.abs(v);
  return `${v < 0 ? '-' : ''}${Math.floor(a / 1000)}.${String(a % 1000).padStart(3, '0')}`;
}

export function parseCommand(body: string): CommandResult {
  const m = /^([GMgm])([0-9]{1,4})(?: +(.*))?$/.exec(body);
  if (!m) return { ok: false, error: 10 };
  const word = m[1].toUpperCase() + String(Number(m[2]));
  const rest = m[3] ?? '';
  if (FILE_COMMANDS.has(word)) {
    const name = FILE_NAME.exec(rest);
    return name ? { ok: true, command: { word, text: name[1] } } : { ok: false, error: 11 };
  }
  if (TEXT_COMMANDS.has(word)) {
    // M117 alone clears the panel's message, as Marlin's does; M850 needs its key.
    return rest.trim() || word === 'M117' ? { ok: true, command: { word, text: rest.trim() } } : { ok: false, error: 11 };
  }
  const params: Record<string, number | null> = {};
  for (const token of rest.split(' ').filter(Boolean)) {
    const letter = token[0].toUpperCase();
    if (!/^[A-Z]$/.test(letter) || letter in params) return { ok: false, error: 11 };
    if (token.length === 1) {
      params[letter] = null;
      continue;
    }
    const v = parseMilli(token.slice(1));
    if (v === null) return { ok: false, error: 11 };
    params[letter] = v;
  }
  return { ok: true, command: { word, params } };
}
