// The simulated Mega's resume judgement, as the firmware makes it (protocol/mega.md "Resume").

import type { NanoReply } from '../protocol/nano';
import type { Checkpoint } from './sd-card';

/** mega.md "Resume": what became of the stop that was next, judged from the Nano's count. */
export function resumeVerdict(cp: Checkpoint, c: NanoReply | null): { from: number; verdict: string } {
  const same = c?.op === 'C' && c.boot === cp.boot;
  if (same && c.fires === cp.fires) return { from: cp.done, verdict: 'had not been sent' };
  if (same && c.fires === cp.fires + 1 && c.whole) return { from: cp.done + 1, verdict: 'had been exposed whole, and counts as done' };
  if (same && c.fires === cp.fires + 1) return { from: cp.done, verdict: 'was cut short, and is exposed again' };
  return { from: cp.done, verdict: "may have been cut short by the printhead's restart, and is exposed again" };
}
