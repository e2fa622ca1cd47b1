import { describe, expect, it } from 'vitest';
import { ATMEGA2560, ATMEGA328P, AVR_BOARDS, chipOfImage } from './chips';
import { avrImage as image } from './avr-image.test-helper';
import { FakeOptiboot, FakeStk500v2 } from './fake-bootloaders';
import { FlashError, flashAvr } from './flash-avr';
import { Stk500v2 } from './stk500v2';

const board = (id: string) => AVR_BOARDS.find((b) => b.id === id)!;

async function failure(p: Promise<unknown>): Promise<FlashError> {
  const e = await p.then(() => null, (x) => x);
  expect(e).toBeInstanceOf(FlashError);
  return e as FlashError;
}

describe('flashing over the bootloader', () => {
  it('writes a Nano image through Optiboot and reads it back', async () => {
    const nano = new FakeOptiboot(ATMEGA328P);
    const bytes = image(26, 20000);
    const phases: string[] = [];
    await flashAvr(nano, board('nano'), bytes, (p) => phases.push(p.phase));
    expect(nano.flash.subarray(0, bytes.length)).toEqual(bytes);
    expect(nano.flash[bytes.length]).toBe(0xff);
    expect(phases[0]).toBe('connecting');
    expect(phases.filter((p) => p === 'writing')).toHaveLength(Math.ceil(20000 / 128));
  });

  it('writes a Mega image past 128 KB through the STK500 v2 bootloader, in its page order', async () => {
    const mega = new FakeStk500v2(ATMEGA2560);
    mega.flash.fill(0x00, 0, 4096); // an old firmware: the bootloader's own erases must clear it
    const bytes = image(57, 140000);
    await flashAvr(mega, board('mega'), bytes);
    expect(mega.flash.subarray(0, bytes.length)).toEqual(bytes);
  });

  it('signs on to the STK500 v2 bootloader by name', async () => {
    expect(await new Stk500v2(new FakeStk500v2(ATMEGA2560)).signOn()).toBe('AVRISP_2');
  });

  it('refuses another chip before writing anything', async () => {
    const mega = new FakeStk500v2(ATMEGA2560);
    const e = await failure(flashAvr(mega, { ...board('mega'), chip: ATMEGA328P }, image(26, 1000)));
    expect(e.failure).toBe('wrong-chip');
    expect(e.message).toContain('has an ATmega2560');
    expect(mega.pagesWritten).toBe(0);
  });

  it('refuses an image built for another chip, or too big for the flash beside the bootloader', async () => {
    expect(chipOfImage(image(57, 2000))).toBe(ATMEGA2560);
    expect(chipOfImage(image(26, 2000))).toBe(ATMEGA328P);
    expect((await failure(flashAvr(new FakeOptiboot(ATMEGA328P), board('nano'), image(57, 2000)))).failure).toBe('image-for-other-chip');
    // boards.txt's maximum_size for both Nanos: Optiboot's Nano is fused for a 2 KB boot section too.
    const big = await failure(flashAvr(new FakeOptiboot(ATMEGA328P), board('nano'), image(26, 30721)));
    expect(big.failure).toBe('image-too-big');
    expect(big.message).toContain('takes 30720 B below its 2048 B boot section');
    const optiboot = new FakeOptiboot(ATMEGA328P);
    await flashAvr(optiboot, board('nano'), image(26, 30720));
    expect(optiboot.pagesWritten).toBe(240);
    expect((await failure(flashAvr(new FakeOptiboot(ATMEGA328P), board('nano-old'), image(26, 31000)))).message).toContain('30720 B');
    expect((await failure(flashAvr(new FakeStk500v2(ATMEGA2560), board('mega'), image(57, 253953)))).message).toContain('takes 253952 B below its 8192 B boot section');
  });

  it('says the bootloader is still there when the cable is pulled mid-write', async () => {
    const nano = new FakeOptiboot(ATMEGA328P);
    nano.pullAfterPages = 40;
    const e = await failure(flashAvr(nano, board('nano'), image(26, 20000)));
    expect(e.failure).toBe('cable-pulled');
    expect(e.message).toMatch(/page 41 of 157.*bootloader.*still there.*flash again/s);
  });

  it('says so when nothing answers at the baud rate', async () => {
    const silent = { write: async () => {}, read: (n: number, ms: number) => new FakeOptiboot(ATMEGA328P).read(n, Math.min(ms, 5)), discard() {} };
    const e = await failure(flashAvr(silent, board('nano'), image(26, 1000)));
    expect(e.failure).toBe('no-bootloader');
    expect(e.message).toContain('old bootloader (57600 baud)');
  });
});

describe('a board that speaks the other protocol', () => {
  it('is named by its chip: a Nano where the Mega was picked', async () => {
    const nano = new FakeOptiboot(ATMEGA328P);
    const e = await failure(flashAvr(nano, board('mega'), image(57, 3000)));
    expect(e.failure).toBe('wrong-chip');
    expect(e.message).toContain('has an ATmega328P, not the ATmega2560');
    expect(nano.pagesWritten).toBe(0);
  });

  it('is named by its chip: a Mega where the Nano was picked', async () => {
    const e = await failure(flashAvr(new FakeStk500v2(ATMEGA2560), board('nano'), image(26, 3000)));
    expect(e.message).toContain('has an ATmega2560, not the ATmega328P');
  });
});
