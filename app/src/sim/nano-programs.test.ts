import { describe, expect, it } from 'vitest';
import { checkEvents, programLines, type ScanEvent } from '../protocol/scan-program';
import { cases, loadVectors, vectorCounter } from '../protocol/vectors.fixture';
import { VirtualClock } from './clock';
import { DEFAULT_NANO, NanoModel } from './nano-model';
import { NanoPrograms, PASS, SEAL } from './nano-programs';

const v = loadVectors('nano-program.json');
const count = vectorCounter('nano-program.json');

/** Sends lines to the simulated Nano; returns its replies. */
function send(nano: NanoModel, lines: string[]): string[] {
  return lines.map((l) => nano.command(`${l}\n`)).filter((r): r is string => r !== null);
}

/**
 * Records every change of the lit mask, [µs, mask], by stepping the clock event by event, and polls
 * Q every 20 ms as a Mega running a pass does (a chain that hears nothing for 50 ms is cut).
 */
function run(clock: VirtualClock, nano: NanoModel, untilUs: number, poll = true): [number, number][] {
  const seen: [number, number][] = [];
  let last = nano.lit;
  let nextPoll = clock.now + 20_000;
  while (Math.min(clock.next, poll ? nextPoll : Infinity) <= untilUs) {
    if (poll && nextPoll <= clock.next) {
      clock.advanceTo(nextPoll);
      nano.command('Q\n');
      nextPoll += 20_000;
    } else clock.advanceTo(clock.next);
    if (nano.lit !== last) seen.push([clock.now, (last = nano.lit)]);
  }
  clock.advanceTo(untilUs);
  return seen;
}


describe('the simulated Nano runs scan programs as nano.md says', () => {
  it.each(cases(v.programs, 'name'))('%s: each program arms, and G runs every event on time', (_n, c: any) => {
    const clock = new VirtualClock();
    const nano = new NanoModel(clock);
    const lines: string[] = c.lines;
    const programs: string[][] = [[]];
    for (const l of lines) {
      programs[programs.length - 1].push(l);
      if (l.startsWith('K:')) programs.push([]);
    }
    programs.pop();
    // The first two programs before the start; each further one as soon as a buffer is free.
    for (const p of programs.slice(0, 2)) expect(send(nano, p)).toEqual(['K:0\n']);
    send(nano, ['G']);
    const g = clock.now;
    const seen: [number, number][] = [];
    for (const p of programs.slice(2)) {
      while (nano.programs.free === 0) seen.push(...run(clock, nano, clock.next));
      expect(send(nano, p)).toEqual(['K:0\n']);
    }
    seen.push(...run(clock, nano, g + 1000 + c.events[c.events.length - 1][0] + 10));
    expect(seen).toEqual((c.events as ScanEvent[]).map(([t, m]) => [g + 1000 + t, m]));
    expect(send(nano, ['Q', 'C'])).toEqual([`Q:2,0,${PASS.WHOLE}\n`, 'C:1,1,1\n']);
  });

  it('cuts a chain whose continuation is not armed in time, and counts it not whole', () => {
    const clock = new VirtualClock();
    const nano = new NanoModel(clock);
    const events: ScanEvent[] = Array.from({ length: 70 }, (_, i) => [i * 100, i % 2 ? 0 : 1]);
    const lines = programLines(events);
    send(nano, lines.slice(0, lines.indexOf(lines.find((l) => l.startsWith('K:'))!) + 1));
    send(nano, ['G']);
    run(clock, nano, clock.now + 1000 + 64 * 100);
    expect(nano.lit).toBe(0);
    expect(send(nano, ['Q', 'C'])).toEqual([`Q:2,0,${PASS.UNDERRUN}\n`, 'C:1,1,0\n']);
  });

  it('R cuts a running chain at once and drops what was armed', () => {
    const clock = new VirtualClock();
    const nano = new NanoModel(clock);
    send(nano, programLines([[0, 15], [500_000, 0]]));
    send(nano, ['G']);
    run(clock, nano, clock.now + 2000);
    expect(nano.lit).toBe(15);
    send(nano, ['R']);
    expect(nano.lit).toBe(0);
    run(clock, nano, clock.now + 600_000);
    expect(nano.lit).toBe(0);
    expect(send(nano, ['Q', 'C'])).toEqual([`Q:2,0,${PASS.CUT_BY_RESET}\n`, 'C:1,1,0\n']);
  });

  it('cuts a chain whose Mega falls silent for 50 ms: the head has stopped with it', () => {
    const clock = new VirtualClock();
    const nano = new NanoModel(clock);
    send(nano, programLines([[0, 1], [40_000, 3], [200_000, 0]]));
    send(nano, ['G']);
    const g = clock.now;
    expect(run(clock, nano, g + 300_000, false)).toEqual([[g + 1000, 1], [g + 41_000, 3], [g + 50_001, 0]]);
    expect(send(nano, ['Q', 'C'])).toEqual([`Q:2,0,${PASS.CUT_BY_SILENCE}\n`, 'C:1,1,0\n']);
  });

  it('refuses a G with nothing armed, and an F while a chain runs', () => {
    const clock = new VirtualClock();
    const nano = new NanoModel(clock);
    send(nano, ['G']);
    expect(send(nano, ['Q'])).toEqual([`Q:2,0,${PASS.REFUSED}\n`]);
    send(nano, programLines([[0, 1], [100_000, 0]]));
    send(nano, ['G']);
    run(clock, nano, clock.now + 5000);
    send(nano, ['F:2,100,100,100,100']);
    expect(nano.lit).toBe(1);
    expect(send(nano, ['E'])).toEqual(['E:8\n']); // BUSY
  });
});

describe('scan-program sessions (nano-program.json): the simulated Nano answers as the firmware does', () => {
  it.each(cases(v.sessions, 'name'))('%s', (_n, c: any) => {
    const clock = new VirtualClock();
    const nano = new NanoModel(clock, { ...DEFAULT_NANO, capUs: v.capUs });
    for (const step of c.steps) {
      if (step.run) {
        while (clock.next < Infinity) clock.advanceTo(clock.next);
        continue;
      }
      expect(nano.command(`${step.send}\n`) ?? '', step.send).toBe(step.reply ? `${step.reply}\n` : '');
    }
    count();
  });
});

describe('NanoPrograms seals as the firmware does', () => {
  const seal = (p: NanoPrograms, events: [number, number][], flags: number) => {
    p.append(`A:0,${events.map(([d, m]) => `${d},${m}`).join(',')}`);
    return p.seal(`K:${flags},${events.length},${checkEvents(events)}`);
  };

  it('answers every refusal with its code', () => {
    const p = new NanoPrograms(1000);
    expect(p.seal('K:0,1,0')).toBe(SEAL.NO_LOAD);
    p.append('A:0,0,1,5,0');
    expect(p.seal(`K:0,1,${checkEvents([[0, 1], [5, 0]])}`)).toBe(SEAL.MISMATCH);
    expect(seal(p, [[0, 1], [5, 2]], 0)).toBe(SEAL.ENDS_LIT);
    expect(seal(p, [[0, 1], [1001, 0]], 0)).toBe(SEAL.CAPPED);
    expect(seal(p, [[5, 0]], 1)).toBe(SEAL.BAD_START);
    expect(seal(p, [[0, 1], [600, 1]], 2)).toBe(SEAL.ARMED);
    expect(seal(p, [[401, 0]], 1)).toBe(SEAL.CAPPED); // 1001 µs on across the two programs
    expect(seal(p, [[400, 0]], 1)).toBe(SEAL.ARMED);
    expect(seal(p, [[0, 1], [5, 0]], 0)).toBe(SEAL.NO_BUFFER);
    p.discard(PASS.CUT_BY_RESET);
    p.append('A:0,0,0');
    for (let q = 1; q <= 13; q++) p.append(`A:${q},10,1,10,0,10,1,10,0,10,1`); // 66 events in all
    expect(p.seal('K:0,64,0')).toBe(SEAL.TOO_MANY);
    expect(p.append('A:0,1,16')).toBe(false);
  });
});
