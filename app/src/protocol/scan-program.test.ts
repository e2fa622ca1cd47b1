import { describe, expect, it } from 'vitest';
import { checkEvents, mergeLight, packWord, parseAppend, parsePacked, parseSeal, programLines, PROGRAM_EVENTS, PROGRAM_START_LEAD_US, type ScanEvent } from './scan-program';
import { cases, loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('nano-program.json');
const count = vectorCounter('nano-program.json');

describe('scan program vectors', () => {
  it('agrees on the limits', () => {
    expect(PROGRAM_EVENTS).toBe(v.maxEvents);
    expect(PROGRAM_START_LEAD_US).toBe(v.startLeadUs);
  });

  it.each(cases(v.programs, 'name'))('%s: light merges into events and events into lines', (_n, c: any) => {
    expect(mergeLight(c.leds)).toEqual(c.events);
    expect(programLines(c.events)).toEqual(c.lines);
    count();
  });

  it.each(cases(v.programs, 'name'))('%s: the B lines and the A lines parse back to the events and their checks', (_n, c: any) => {
    for (const form of [c.lines, c.appendLines] as string[][]) {
    const events: ScanEvent[] = [];
    let t = 0;
    let program: [number, number][] = [];
    for (const line of form) {
      if (line.startsWith('K:')) {
        const seal = parseSeal(line)!;
        expect(seal.events).toBe(program.length);
        expect(seal.check).toBe(checkEvents(program));
        program = [];
        continue;
      }
      for (const [d, m] of (line.startsWith('B:') ? parsePacked(line) : parseAppend(line))!.events) {
        t += d;
        events.push([t, m]);
        program.push([d, m]);
      }
    }
    expect(events).toEqual(c.events);
    }
  });

  it.each(v.packedWords as [number, string][])('the word %d packs as %s and back', (w, line) => {
    expect(`B:0,${packWord(w)}`).toBe(line);
    expect(parsePacked(line)).toEqual({ seq: 0, events: [[Math.floor(w / 16), w % 16]] });
    count();
  });

  it.each(cases(v.bad, 'why'))('bad line (%s) is refused', (_w, c: any) => {
    const parse = c.line.startsWith('K') ? parseSeal : c.line.startsWith('B') ? parsePacked : parseAppend;
    expect(parse(c.line)).toBeNull();
    count();
  });
});

describe('programLines', () => {
  it('refuses events out of order or too far apart', () => {
    expect(() => programLines([])).toThrow(RangeError);
    expect(() => programLines([[10, 1], [10, 0]])).toThrow(RangeError);
    expect(() => programLines([[10, 1], [5, 0]])).toThrow(RangeError);
    expect(() => programLines([[10, 1], [10 + 2 ** 28, 0]])).toThrow(RangeError);
    expect(() => programLines([[0, 16]])).toThrow(RangeError);
  });

  it('keeps an LED on across touching intervals', () => {
    expect(mergeLight([[[0, 2000], [2000, 4000]], [], [], []])).toEqual([[0, 1], [4000, 0]]);
  });
});
