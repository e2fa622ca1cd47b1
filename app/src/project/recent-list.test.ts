import { describe, expect, it } from 'vitest';
import { MAX_RECENT, withRecent, type RecentEntry } from './recent-list';

const entry = (id: string, name = id): RecentEntry => ({ id, name, savedAt: '2026-11-21T10:00:00Z', bytes: 10, why: 'saved' });

describe('recent projects', () => {
  it('puts the newest first and keeps one entry per name', () => {
    const { list, dropped } = withRecent([entry('a'), entry('b')], entry('b2', 'b'));
    expect(list.map((e) => e.id)).toEqual(['b2', 'a']);
    expect(dropped).toEqual(['b']);
  });

  it('keeps at most a few, dropping the oldest', () => {
    let list: RecentEntry[] = [];
    const dropped: string[] = [];
    for (let i = 0; i < MAX_RECENT + 2; i++) {
      const r = withRecent(list, entry(`p${i}`));
      list = r.list;
      dropped.push(...r.dropped);
    }
    expect(list).toHaveLength(MAX_RECENT);
    expect(list[0].id).toBe(`p${MAX_RECENT + 1}`);
    expect(dropped).toEqual(['p0', 'p1']);
  });

  it('does not drop the file of an entry saved again under the same id', () => {
    expect(withRecent([entry('a')], entry('a')).dropped).toEqual([]);
  });
});
