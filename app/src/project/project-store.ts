// Projects kept in the browser's IndexedDB (through idb-keyval): the autosave, rewritten after
// edits and before every job, and the recent projects. Files are kept as the same JSON text a
// saved file has, so what is kept here opens exactly as a file would.

import { createStore, del, get, set, update, type UseStore } from 'idb-keyval';
import { withRecent, type RecentEntry } from './recent-list';

export interface Autosave {
  name: string;
  savedAt: string;
  text: string;
}

let db: UseStore | null = null;
const store = () => (db ??= createStore('uv-exposure', 'projects'));

export function saveAutosave(name: string, text: string): Promise<void> {
  return set('autosave', { name, savedAt: new Date().toISOString(), text } satisfies Autosave, store());
}

export function loadAutosave(): Promise<Autosave | undefined> {
  return get<Autosave>('autosave', store());
}

export async function remember(name: string, text: string, why: RecentEntry['why']): Promise<RecentEntry> {
  const entry: RecentEntry = { id: `project:${name}`, name, savedAt: new Date().toISOString(), bytes: text.length, why };
  await set(entry.id, text, store());
  let dropped: string[] = [];
  await update<RecentEntry[]>('recent', (list) => {
    const r = withRecent(list ?? [], entry);
    dropped = r.dropped;
    return r.list;
  }, store());
  await Promise.all(dropped.map((id) => del(id, store())));
  return entry;
}

export async function recentProjects(): Promise<RecentEntry[]> {
  return (await get<RecentEntry[]>('recent', store())) ?? [];
}

export async function recentText(id: string): Promise<string> {
  const text = await get<string>(id, store());
  if (text === undefined) throw new Error('that project is no longer kept in this browser');
  return text;
}
