// The two STK500 clients against bootloaders that behave as boards do: deaf for the start-up time-out
// after a reset, and with stray bytes on the line.
import { describe, expect, it } from 'vitest';
import { LinkTimeout } from './byte-link';
import { ATMEGA2560, ATMEGA328P } from './chips';
import { FakeOptiboot, FakeStk500v2 } from './fake-bootloaders';
import { Stk500v1 } from './stk500v1';
import { Stk500v2 } from './stk500v2';

/** Drops what it is sent for `deafMs` after it is made, as a chip in its start-up time-out does. */
function deaf<T extends FakeOptiboot | FakeStk500v2>(board: T, deafMs: number): T {
  const until = Date.now() + deafMs;
  const write = board.write.bind(board);
  board.write = async (bytes) => {
    if (Date.now() >= until) await write(bytes);
  };
  return board;
}

/** Puts noise before every answer: bytes that are neither STK500 v2's message start nor v1's INSYNC. */
function noisy<T extends FakeOptiboot | FakeStk500v2>(board: T): T {
  const answer = (board as unknown as { answer(b: ArrayLike<number>): void }).answer.bind(board);
  (board as unknown as { answer(b: ArrayLike<number>): void }).answer = (b) => answer([0x00, 0xfe, 0x10, ...Array.from(b)]);
  return board;
}

describe('STK500 v2 (the Mega)', () => {
  it('signs on to a bootloader that was deaf for its first 300 ms, by asking again', async () => {
    const t0 = Date.now();
    expect(await new Stk500v2(deaf(new FakeStk500v2(ATMEGA2560), 300)).signOn()).toBe('AVRISP_2');
    expect(Date.now() - t0).toBeGreaterThanOrEqual(300);
  });

  it('gives up after about 1.5 s of silence', async () => {
    const t0 = Date.now();
    await expect(new Stk500v2(deaf(new FakeStk500v2(ATMEGA2560), 10_000)).signOn()).rejects.toBeInstanceOf(LinkTimeout);
    expect(Date.now() - t0).toBeGreaterThanOrEqual(1400);
    expect(Date.now() - t0).toBeLessThan(2200);
  });

  it('skips stray bytes before each answer', async () => {
    const v2 = new Stk500v2(noisy(new FakeStk500v2(ATMEGA2560)));
    expect(await v2.signOn()).toBe('AVRISP_2');
    expect(Array.from(await v2.signature())).toEqual(ATMEGA2560.signature);
  });
});

describe('STK500 v1 (the Nanos)', () => {
  it('gets in sync with a bootloader that was deaf for its first 300 ms', async () => {
    const v1 = new Stk500v1(deaf(new FakeOptiboot(ATMEGA328P), 300));
    await v1.sync();
    expect(Array.from(await v1.signature())).toEqual(ATMEGA328P.signature);
  });

  it('gets in sync, and answers, through stray bytes before INSYNC', async () => {
    const v1 = new Stk500v1(noisy(new FakeOptiboot(ATMEGA328P)));
    await v1.sync();
    expect(Array.from(await v1.signature())).toEqual(ATMEGA328P.signature);
  });

  it('gives up after about 1.5 s of silence', async () => {
    const t0 = Date.now();
    await expect(new Stk500v1(deaf(new FakeOptiboot(ATMEGA328P), 10_000)).sync()).rejects.toBeInstanceOf(LinkTimeout);
    expect(Date.now() - t0).toBeLessThan(2200);
  });
});
