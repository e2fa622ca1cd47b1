// The console's log: each line from or to the printer with its time and a level, kept to a bound,
// and the filter the console shows it through.

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

export class ConsoleLog {
  readonly entries: Entry[] = [];
  constructor(readonly max = 2000) {}

  add(text: string, level: Level = levelOf(text), atMs = Date.now()): Entry {
    const entry = { atMs, level, text };
    this.entries.push(entry);
    if (this.entries.length > this.max) this.entries.splice(0, this.entries.length - this.max);
    return entry;
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
