// The dialect's numbers, held as fixed point in thousandths (protocol/mega.md §1), as the app reads and
// writes them: the mm of the Mega's position and probe reports. Its commands are the Mega's to parse.

/** The largest magnitude a number may have: 2000000.000. */
const MAX_MILLI = 2_000_000_000;

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
