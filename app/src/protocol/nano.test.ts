// What the app takes from the printhead link (nano.ts) against the vectors. The app never talks to the
// Nano: the link's codec is the firmware's C++, which firmware/common/protocol/test/nano_codec_test.cpp
// checks on every section of nano.json, and the nano_line and printhead_link fuzzers (firmware/fuzz/)
// run on hostile bytes.
import { describe, expect, it } from 'vitest';
import { formatDeciC, NANO_LINK_BAUDS, parseDeciC, PROGRAM_EVENTS, SENSOR_COUNT } from './nano';
import { loadVectors, vectorCounter } from './vectors.fixture';

const v = loadVectors('nano.json');
const count = vectorCounter('nano.json');
const temps: { line: string; reply: { deciC: number[] } }[] = v.replies.filter((c: any) => c.reply.op === 'T');

describe('the printhead link, as the app knows it', () => {
  it('holds as many events in a program as nano-program.json', () => {
    // The program lines are the Mega's to write and the Nano's to read (nano-program.json binds the
    // C++); the app reads only how many events a program holds, to lay a pass's dose records.
    expect(PROGRAM_EVENTS).toBe(loadVectors('nano-program.json').maxEvents);
  });

  it("knows the link speeds an L may ask for: those of nano.json's L commands", () => {
    const asked: number[] = v.commands.filter((c: any) => c.command.op === 'L').map((c: any) => c.command.baud);
    expect([...NANO_LINK_BAUDS].sort((a, b) => a - b)).toEqual([...new Set(asked)].sort((a, b) => a - b));
  });

  it('reads and writes tenths of a degree as the T replies carry them, one a sensor', () => {
    expect(temps.length).toBeGreaterThan(0);
    for (const c of temps) {
      const fields = c.line.slice('T:'.length, -1).split(',');
      expect(fields).toHaveLength(SENSOR_COUNT);
      expect(fields.map((f) => parseDeciC(f))).toEqual(c.reply.deciC);
      expect(c.reply.deciC.map(formatDeciC)).toEqual(fields);
      count();
    }
  });
});
