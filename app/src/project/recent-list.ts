// The recent projects list: newest first, one entry per project name, at most a few.

export interface RecentEntry {
  /** The key its file is kept under. */
  id: string;
  name: string;
  savedAt: string;
  bytes: number;
  /** Why it was kept: saved to a file, opened, before a job, or when a new project replaced it. */
  why: 'saved' | 'opened' | 'before a job' | 'set aside';
}

export const MAX_RECENT = 8;

/** The list with `entry` first, any older entry of the same name gone; and the ids that fell off. */
export function withRecent(list: readonly RecentEntry[], entry: RecentEntry): { list: RecentEntry[]; dropped: string[] } {
  const rest = list.filter((e) => e.name !== entry.name);
  const all = [entry, ...rest];
  const dropped = [...list.filter((e) => e.name === entry.name && e.id !== entry.id), ...all.slice(MAX_RECENT)].map((e) => e.id);
  return { list: all.slice(0, MAX_RECENT), dropped };
}
