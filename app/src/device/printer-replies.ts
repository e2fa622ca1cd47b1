// What the app reads from the printer's answers: its settings (`M503`), an interrupted job waiting
// to be resumed (`M1000 S`), and whether exposures follow the mesh (bare `M420`).

import type { Reply } from '../protocol/dialect-reply';

/** A job the printer was running when it restarted: its checkpoint is on the card (mega.md "Resume"). */
export interface InterruptedJob {
  file: string;
  done: number;
  stops: number;
}

/** `M503`'s `M850 <key> <value>` lines as a record. */
export function configOf(replies: Reply[]): Record<string, string> {
  const config: Record<string, string> = {};
  for (const r of replies) {
    const m = r.kind === 'other' ? /^M850 (\S+) (.+)$/.exec(r.text) : null;
    if (m) config[m[1]] = m[2];
  }
  return config;
}

/** `M1000 S`'s `JOB:interrupted file=<f> stop=<done>/<total>`, or null for `JOB:idle`. */
export function interruptedOf(replies: Reply[]): InterruptedJob | null {
  for (const r of replies) {
    if (r.kind !== 'job' || r.state !== 'interrupted') continue;
    const [done, stops] = (r.fields.stop ?? '').split('/').map(Number);
    if (r.fields.file && Number.isInteger(done) && Number.isInteger(stops)) return { file: r.fields.file, done, stops };
  }
  return null;
}

/** Bare `M420`'s `echo:leveling on|off`; null from a printer that does not say. */
export function levelingOf(replies: Reply[]): boolean | null {
  for (const r of replies) if (r.kind === 'echo' && /^leveling (on|off)$/.test(r.text)) return r.text === 'leveling on';
  return null;
}
