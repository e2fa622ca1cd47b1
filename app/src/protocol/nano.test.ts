import { describe, expect, it } from 'vitest';
import { LineSplitter } from './line-splitter';
import {
  flashColour, formatNanoCommand, formatNanoReply, NANO_COLOURS, NANO_MAX_LINE,
  nanoLineUsable, parseNanoCommand, parseNanoReply, PROGRAM_EVENTS,
} from './nano';
import { cases, loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('nano.json');
const count = vectorCounter('nano.json');

/** Runs raw bytes through the Nano's framing and parser, as the firmware does. */
function nanoReceive(bytes: string) {
  const split = new LineSplitter(NANO_MAX_LINE).push(bytes);
  return split.filter((l) => l.text !== '' || l.overflow).map((l) => (nanoLineUsable(l) ? parseNanoCommand(l.text) : null));
}

describe('nano link vectors', () => {
  it('agrees on limits and colours', () => {
    expect(NANO_MAX_LINE).toBe(v.maxLine);
    expect(NANO_COLOURS).toEqual(v.colours);
    // The program lines are the Mega's to write and the Nano's to read (nano-program.json binds the
    // C++); the app reads only how many events a program holds, to lay a pass's dose records.
    expect(PROGRAM_EVENTS).toBe(loadVectors('nano-program.json').maxEvents);
    count();
  });

  it.each(cases(v.commands, 'line'))('command %j encodes, parses and flashes', (_l, c: any) => {
    expect(formatNanoCommand(c.command)).toBe(c.line);
    expect(nanoReceive(c.line)).toEqual([c.command]);
    expect(flashColour(c.command.op)).toBe(c.flash);
    count();
  });

  it.each(cases(v.parseOnly, 'line'))('lenient line %j parses', (_l, c: any) => {
    expect(nanoReceive(c.line)).toEqual([c.command]);
    count();
  });

  it.each(cases(v.malformed, 'why'))('malformed (%s) does nothing', (_w, c: any) => {
    expect(nanoReceive(c.line)).toEqual([null]);
    expect(nanoReceive(c.line + 'S\n')).toEqual([null, { op: 'S' }]);
    count();
  });

  it.each(cases(v.replies, 'line'))('reply %j round-trips', (_l, c: any) => {
    expect(parseNanoReply(c.line)).toEqual(c.reply);
    expect(formatNanoReply(c.reply)).toBe(c.line);
    count();
  });

  it.each(cases(v.badReplies, 'line'))('bad reply %j is rejected', (line) => {
    expect(parseNanoReply(line)).toBeNull();
    count();
  });

  it.each(cases(v.streams, 'name'))('stream: %s', (_n, c: any) => {
    // Every split point must give the same lines.
    for (let cut = 0; cut <= c.bytes.length; cut++) {
      const s = new LineSplitter(NANO_MAX_LINE);
      const lines = [...s.push(c.bytes.slice(0, cut)), ...s.push(c.bytes.slice(cut))];
      const kept = lines.filter((l) => l.text !== '' || l.overflow);
      expect(kept.filter(nanoLineUsable).map((l) => l.text)).toEqual(c.lines);
      expect(kept.filter((l) => !nanoLineUsable(l)).length).toBe(c.dropped);
    }
    count();
  });
});

describe('formatting an F', () => {
  it('refuses LEDs past the four and durations past 32 bits, as the C++ codec does', () => {
    expect(() => formatNanoCommand({ op: 'F', mask: 0xa7, durations: [1, 1, 1, 1] })).toThrow(RangeError);
    expect(() => formatNanoCommand({ op: 'F', mask: 1, durations: [2 ** 32, 0, 0, 0] })).toThrow(RangeError);
    expect(() => formatNanoCommand({ op: 'F', mask: 1, durations: [1.5, 0, 0, 0] })).toThrow(RangeError);
    expect(formatNanoCommand({ op: 'F', mask: 15, durations: [0xffffffff, 0, 0, 0] })).toBe('F:15,4294967295,0,0,0\n');
  });
});

describe('formatting an L', () => {
  it('refuses a speed not in the table, as the C++ codec does', () => {
    for (const baud of [0, 9600, 115201, 999999, 2000000, 2 ** 32 + 1000000]) {
      expect(() => formatNanoCommand({ op: 'L', baud })).toThrow(RangeError);
    }
    expect(formatNanoCommand({ op: 'L', baud: 1000000 })).toBe('L:1000000\n');
  });
});
