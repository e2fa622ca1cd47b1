import { existsSync, readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { ATMEGA2560, ATMEGA328P, AVR_BOARDS, bootSectionBytes, chipOfImage, imageMismatch, readImageStart } from './chips';
import { avrImage } from './avr-image.test-helper';
import { parseIntelHex } from './intel-hex';

describe("an image's chip, read off its vector table and start-up code", () => {
  it('reads the stack top and EIND as avr-libc sets them', () => {
    expect(readImageStart(avrImage(26, 400))).toEqual({ jumps: 26, stackTop: 0x08ff, setsEind: false });
    expect(readImageStart(avrImage(57, 400))).toEqual({ jumps: 57, stackTop: 0x21ff, setsEind: true });
  });

  it("takes each board's own image", () => {
    expect(imageMismatch(ATMEGA328P, avrImage(26, 4000))).toBeNull();
    expect(imageMismatch(ATMEGA2560, avrImage(57, 4000))).toBeNull();
    expect(chipOfImage(avrImage(57, 400))?.name).toBe('ATmega2560');
  });

  it.each([
    ['an ATmega168 image (a 328P\'s vector table, half its RAM)', ATMEGA328P, avrImage(26, 4000, 0x04ff, false), 'built for the ATmega168'],
    ['an ATmega1280 image (a 2560\'s vector table, no EIND)', ATMEGA2560, avrImage(57, 4000, 0x21ff, false), 'built for the ATmega1280'],
    ['an ATmega32U4 image (Leonardo, Pro Micro)', ATMEGA328P, avrImage(43, 4000, 0x0aff), 'built for the ATmega32U4'],
    ['an ATmega644P image', ATMEGA2560, avrImage(31, 4000, 0x10ff), 'built for the ATmega644P'],
    ['a 2560 image on the Nano', ATMEGA328P, avrImage(57, 4000), 'built for the ATmega2560'],
    ['a 328P image on the Mega', ATMEGA2560, avrImage(26, 4000), 'built for the ATmega328P'],
    ['an ATmega8 image (rjmp vectors)', ATMEGA328P, Uint8Array.from({ length: 400 }, (_, i) => (i % 2 ? 0xc0 : 0x12)), 'does not start with a vector table of jmp'],
    ['a file that is not firmware', ATMEGA328P, new TextEncoder().encode('hello, this is a text file'.repeat(20)), 'does not start with a vector table of jmp'],
    ['a table of an unknown length', ATMEGA328P, avrImage(20, 400, 0x0123), 'a vector table of 20 jumps; the ATmega328P\'s has 26'],
    ['a 328P table whose code sets another stack', ATMEGA328P, avrImage(26, 400, 0x0123), 'puts the stack at 0x123'],
  ])('refuses %s', (_, chip, bytes, message) => {
    expect(imageMismatch(chip, bytes)).toContain(message);
  });
});

describe('the boards as shipped', () => {
  it("limits each image to boards.txt's maximum_size, the flash below the fused boot section", () => {
    const by = (id: string) => AVR_BOARDS.find((b) => b.id === id)!;
    expect(by('nano').maximumSize).toBe(30720);
    expect(by('nano-old').maximumSize).toBe(30720);
    expect(by('mega').maximumSize).toBe(253952);
    expect(bootSectionBytes(by('nano'))).toBe(2048);
  });
});

describe('the images the build makes', () => {
  it.runIf(existsSync('build/avr/nano.hex') && existsSync('build/avr/mega.hex'))('are each taken by their own chip and refused by the other', () => {
    const nano = parseIntelHex(readFileSync('build/avr/nano.hex', 'utf8')).bytes;
    const mega = parseIntelHex(readFileSync('build/avr/mega.hex', 'utf8')).bytes;
    expect(readImageStart(nano)).toEqual({ jumps: 26, stackTop: 0x08ff, setsEind: false });
    expect(readImageStart(mega)).toEqual({ jumps: 57, stackTop: 0x21ff, setsEind: true });
    expect(imageMismatch(ATMEGA328P, nano)).toBeNull();
    expect(imageMismatch(ATMEGA2560, mega)).toBeNull();
    expect(imageMismatch(ATMEGA328P, mega)).toContain('built for the ATmega2560');
  });
});
