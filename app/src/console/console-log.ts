// The console's log: each line from or to the printer with its time and a level, kept to a bound
// per level, and the filter the console shows it through.

/** `reply`: a line answering what the user typed, shown whatever its kind (M105's T:, M114's X:). */
export type Level = 'error' | 'warning' | 'info' | 'report' | 'reply' | 'sent' | 'link';

export interface Entry {
  atMs: number;
  level: Level;
  text: string;
}

/** A line's level: errors and faults stand out, reports (sent every second) can be hidden. */
export function levelOf(line: string): Level {
  if (/^(Error:|FAULT:|!!|echo:E[0-9])/.test(line)) return 'error'; // echo:E<code>: a refused command (mega.md §2)
  if (/^(Resend:|rs |PROBE:alarm|echo:.*(warning|refused|cannot))/i.test(line)) return 'warning';
  if (/^(T:|X:|JOB:|busy:)/.test(line)) return 'report';
  if (/^ok\b/.test(line)) return 'link';
  return 'info';
}

/**
 * How many of the newest lines of each level are kept. The auto-reports and the link's oks come
 * several a second for hours: under one bound for all, they pushed out what the user typed, its
 * replies and the faults (issue 29, item 11). Each level has its own bound instead.
 */
export const KEPT: Readonly<Record<Level, number>> = {
  error: 2000,
  warning: 2000,
  sent: 2000,
  reply: 2000,
  info: 2000,
  report: 600,
  link: 600,
};

export class ConsoleLog {
  readonly entries: Entry[] = [];
  /** Every line ever added, kept or not. */
  added = 0;
  readonly #kept: Readonly<Record<Level, number>>;
  /** Lines of each level, as added (a reply marked later still counts as what it came as, until a trim). */
  #count: Record<Level, number> = { error: 0, warning: 0, info: 0, report: 0, reply: 0, sent: 0, link: 0 };

  constructor(kept: Partial<Record<Level, number>> = {}) {
    this.#kept = { ...KEPT, ...kept };
  }

  add(text: string, level: Level = levelOf(text), atMs = Date.now()): Entry {
    const entry = { atMs, level, text };
    this.entries.push(entry);
    this.added++;
    // Trimming walks the whole log: it waits until a level is a quarter past its bound.
    if (++this.#count[level] > this.#kept[level] * 1.25) this.trim();
    return entry;
  }

  /** Drops the lines past each level's bound, oldest first; the others keep their order. */
  trim(): void {
    const left = { ...this.#kept };
    const count = { error: 0, warning: 0, info: 0, report: 0, reply: 0, sent: 0, link: 0 };
    const keep: boolean[] = new Array(this.entries.length);
    for (let i = this.entries.length - 1; i >= 0; i--) {
      const level = this.entries[i].level;
      if ((keep[i] = left[level]-- > 0)) count[level]++;
    }
    let n = 0;
    for (let i = 0; i < this.entries.length; i++) if (keep[i]) this.entries[n++] = this.entries[i];
    this.entries.length = n;
    this.#count = count;
  }

  /**
   * The lines of a reply block answer the line the user typed: a report among them (M105's
   * temperatures, M114's position) is shown as a reply, while auto-reports stay filtered.
   */
  markReplies(entries: Entry[]): void {
    for (const e of entries) if (e.level === 'report' || e.level === 'info') e.level = 'reply';
  }
}

export interface LogFilter {
  text: string;
  /** Levels shown; the link's own lines (ok, resend) only with the debug toggle. */
  levels: Set<Level>;
}

export const DEFAULT_LEVELS: Level[] = ['error', 'warning', 'info', 'reply', 'sent'];

export function filterLog(entries: readonly Entry[], f: LogFilter, last = 300): Entry[] {
  const needle = f.text.trim().toLowerCase();
  const out: Entry[] = [];
  for (let i = entries.length - 1; i >= 0 && out.length < last; i--) {
    const e = entries[i];
    if (!f.levels.has(e.level)) continue;
    if (needle && !e.text.toLowerCase().includes(needle)) continue;
    out.push(e);
  }
  return out.reverse();
}
