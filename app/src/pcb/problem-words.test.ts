import { describe, expect, it } from 'vitest';
import { problemsByFile, problemText } from './problem-words';

describe('a board’s problems, one entry per file', () => {
  it('says a message repeated on many lines once, with how often and where', () => {
    const problems = [
      { file: 'AssemblyTop.gdo', message: 'line 1021: skipping impossible arc' },
      ...[544, 889, 1059, 1388, 1389].map((n) => ({ file: 'EtchLayer2Bottom.gdo', message: `line ${n}: skipping impossible arc` })),
      { file: 'EtchLayer2Bottom.gdo', message: 'image mirroring (%MI) is not applied' },
      { file: 'notes.gbr', message: 'the file is empty' },
    ];
    expect(problemsByFile(problems)).toEqual([
      { file: 'AssemblyTop.gdo', messages: ['skipping impossible arc (line 1021)'] },
      { file: 'EtchLayer2Bottom.gdo', messages: ['skipping impossible arc (5 times: lines 544, 889, 1059 and 2 more)', 'image mirroring (%MI) is not applied'] },
      { file: 'notes.gbr', messages: ['the file is empty'] },
    ]);
  });

  it('names two or three lines outright', () => {
    const p = (n: number) => ({ file: 'a.gbr', message: `line ${n}: tool 12 is not defined` });
    expect(problemsByFile([p(3), p(9)])[0].messages).toEqual(['tool 12 is not defined (lines 3, 9)']);
    expect(problemsByFile([p(3), p(9), p(12)])[0].messages).toEqual(['tool 12 is not defined (lines 3, 9, 12)']);
  });

  it('is empty for no problems, and one line a file as text', () => {
    expect(problemsByFile([])).toEqual([]);
    expect(problemText([{ file: 'a.gbr', messages: ['x', 'y'] }, { file: 'b.drl', messages: ['z'] }])).toBe('a.gbr: x; y\nb.drl: z');
  });
});
