// A board's problems as a person reads them: one entry per file, a message said once with the lines it happened on.
import type { BoardProblem } from './read-board';

export interface FileProblems {
  file: string;
  messages: string[];
}

/** Lines named before "and N more". */
const LINES_SHOWN = 3;
const AT_LINE = /^line (\d+): (.*)$/s;

/** The problems grouped by file in the order the files first appear; a message repeated on many lines is said once. */
export function problemsByFile(problems: readonly BoardProblem[]): FileProblems[] {
  const files = new Map<string, Map<string, number[]>>();
  for (const p of problems) {
    let said = files.get(p.file);
    if (!said) files.set(p.file, (said = new Map()));
    const m = AT_LINE.exec(p.message);
    const message = m ? m[2] : p.message;
    const lines = said.get(message) ?? [];
    if (m) lines.push(Number(m[1]));
    said.set(message, lines);
  }
  return [...files].map(([file, said]) => ({ file, messages: [...said].map(([message, lines]) => message + atLines(lines)) }));
}

function atLines(lines: number[]): string {
  if (lines.length === 0) return '';
  if (lines.length === 1) return ` (line ${lines[0]})`;
  const shown = lines.slice(0, LINES_SHOWN).join(', ');
  const more = lines.length - LINES_SHOWN;
  return more > 0 ? ` (${lines.length} times: lines ${shown} and ${more} more)` : ` (lines ${shown})`;
}

/** One line per file, for an error's message. */
export const problemText = (groups: readonly FileProblems[]): string => groups.map((g) => `${g.file}: ${g.messages.join('; ')}`).join('\n');

/** A board none of whose files draws anything: each file's problems, to be shown one file a line. */
export class BoardUnreadable extends Error {
  constructor(readonly problems: FileProblems[]) {
    super(problemText(problems) || 'the board draws nothing');
    this.name = 'BoardUnreadable';
  }
}
