// The boards the app flashes, the chips on them and their bootloaders: where each image may go, and which
// chip an image was built for.

import shipped from '../../../firmware/boot/boards-as-shipped.json';

export interface Chip {
  name: string;
  /** The signature bytes the chip answers (its datasheet's "Signature Bytes"). */
  signature: [number, number, number];
  flashBytes: number;
  /** The flash page: the unit the bootloader erases and writes. */
  pageBytes: number;
  /** Interrupt vectors, each a 4-byte jmp: how the start of an image says which chip it was built for. */
  vectors: number;
  /** RAMEND: where avr-libc's start-up code puts the stack, so where an image's reset code points SP. */
  ramEnd: number;
  /** A 22-bit program counter: avr-libc's start-up code then sets EIND (out 0x3c) right after SP. */
  threeBytePc: boolean;
}

export const ATMEGA328P: Chip = { name: 'ATmega328P', signature: [0x1e, 0x95, 0x0f], flashBytes: 32768, pageBytes: 128, vectors: 26, ramEnd: 0x08ff, threeBytePc: false };
export const ATMEGA2560: Chip = { name: 'ATmega2560', signature: [0x1e, 0x98, 0x01], flashBytes: 262144, pageBytes: 256, vectors: 57, ramEnd: 0x21ff, threeBytePc: true };
export const CHIPS = [ATMEGA328P, ATMEGA2560];

/**
 * Chips whose images people have at hand (other Arduinos), known only to name them when refused:
 * their vector count and RAMEND from avr-libc's io headers (iom168.h, iom32u4.h, iom644p.h, iom1280.h).
 */
const OTHER_CHIPS: Pick<Chip, 'name' | 'vectors' | 'ramEnd' | 'threeBytePc'>[] = [
  { name: 'ATmega168', vectors: 26, ramEnd: 0x04ff, threeBytePc: false },
  { name: 'ATmega32U4', vectors: 43, ramEnd: 0x0aff, threeBytePc: false },
  { name: 'ATmega644P', vectors: 31, ramEnd: 0x10ff, threeBytePc: false },
  { name: 'ATmega1280', vectors: 57, ramEnd: 0x21ff, threeBytePc: false },
];

export type AvrBoardId = 'nano' | 'nano-old' | 'mega';
export type BoardId = AvrBoardId | 'esp8266' | 'esp32';

export interface AvrBoard {
  id: AvrBoardId;
  /** Which image it takes: the manifest's board name. */
  image: 'nano' | 'mega';
  name: string;
  chip: Chip;
  protocol: 'stk500v1' | 'stk500v2';
  baud: number;
  /** The most an image may hold: boards.txt's upload.maximum_size, the flash below the fused boot section. */
  maximumSize: number;
  /** How to plug it in, said before the port is picked. */
  plugIn: string;
  /** The firmware's own baud, for asking it its version afterwards. */
  firmwareBaud: number;
}

// Both Nano bootloaders sit in the same 2 KB boot section: Arduino fuses Optiboot's Nano as the old one.
const NANO_MAX = shipped.boards.nano.maximumSize;
const MEGA_MAX = shipped.boards.mega.maximumSize;

export const AVR_BOARDS: AvrBoard[] = [
  {
    id: 'nano', image: 'nano', name: 'Nano (printhead), Optiboot', chip: ATMEGA328P, protocol: 'stk500v1', baud: 115200, maximumSize: NANO_MAX, firmwareBaud: 115200,
    plugIn: 'Unplug the Nano from the Mega (its TX and RX must be free), then plug the Nano into this computer by its USB port.',
  },
  {
    id: 'nano-old', image: 'nano', name: 'Nano (printhead), old bootloader', chip: ATMEGA328P, protocol: 'stk500v1', baud: 57600, maximumSize: NANO_MAX, firmwareBaud: 115200,
    plugIn: 'Unplug the Nano from the Mega (its TX and RX must be free), then plug the Nano into this computer by its USB port. Nanos sold before 2018 (and many clones) have this bootloader.',
  },
  {
    id: 'mega', image: 'mega', name: 'Mega 2560 (motion controller)', chip: ATMEGA2560, protocol: 'stk500v2', baud: 115200, maximumSize: MEGA_MAX, firmwareBaud: 115200,
    plugIn: 'Plug the Mega into this computer by its USB port. On a Mega+WiFi board, set DIP switches 3 and 4 ON and the others OFF (USB to the ATmega2560).',
  },
];

export const flashLimit = (b: AvrBoard) => b.maximumSize;
export const bootSectionBytes = (b: AvrBoard) => b.chip.flashBytes - b.maximumSize;

/** What the start of an image says about the chip it was built for. */
export interface ImageStart {
  /** Leading 4-byte jmps (0x940c): the vector table's length. */
  jumps: number;
  /** The stack top its reset code loads into r28:r29 (avr-libc's __init), when found. */
  stackTop: number | null;
  /** Whether that code sets EIND, as it does for chips with a 22-bit program counter. */
  setsEind: boolean;
}

const word = (b: Uint8Array, at: number) => (at + 1 < b.length ? b[at] | (b[at + 1] << 8) : -1);

export function readImageStart(bytes: Uint8Array): ImageStart {
  let jumps = 0;
  // jmp k: 1001 010k kkkk 110k, then k's low 16 bits; a target past the first 128 KB (a Mega image
  // over 128 KB puts some handlers there) sets k's high bits in the first word.
  while ((word(bytes, jumps * 4) & 0xfe0e) === 0x940c) jumps++;
  let stackTop: number | null = null;
  let setsEind = false;
  if (jumps > 0) {
    // The reset vector's target (a word address; the image's first 128 KB need no high bits).
    const reset = word(bytes, 2) * 2;
    let low = -1;
    let high = -1;
    let spSetAt = -1;
    // __init's first words: SP from r28:r29 (out 0x3e, out 0x3d), then, on a 22-bit PC, EIND (out 0x3c).
    for (let at = reset; at >= 0 && at < reset + 24 && at + 1 < bytes.length; at += 2) {
      const w = word(bytes, at);
      // ldi Rd, K: 1110 KKKK dddd KKKK, Rd = 16 + dddd.
      if ((w & 0xf000) === 0xe000) {
        const rd = 16 + ((w >> 4) & 0xf);
        const k = ((w >> 4) & 0xf0) | (w & 0x0f);
        if (rd === 28 && low < 0) low = k;
        if (rd === 29 && high < 0) high = k;
      }
      // out A, Rr: 1011 1AAr rrrr AAAA.
      const port = (w & 0xf800) === 0xb800 ? ((w >> 5) & 0x30) | (w & 0x0f) : -1;
      if (port === 0x3d && spSetAt < 0) spSetAt = at;
      if (port === 0x3c && spSetAt >= 0 && at <= spSetAt + 4) setsEind = true;
      if (spSetAt >= 0 && at > spSetAt + 4) break;
    }
    if (low >= 0 && high >= 0) stackTop = (high << 8) | low;
  }
  return { jumps, stackTop, setsEind };
}

/** The chip an image was built for, by its vector table and start-up code; null when no known chip fits. */
export function chipOfImage(bytes: Uint8Array): Pick<Chip, 'name' | 'vectors' | 'ramEnd' | 'threeBytePc'> | null {
  const start = readImageStart(bytes);
  const fits = [...CHIPS, ...OTHER_CHIPS].filter(
    (c) => c.vectors === start.jumps && (start.stackTop === null || (c.ramEnd === start.stackTop && c.threeBytePc === start.setsEind)),
  );
  return fits.length === 1 ? fits[0] : null;
}

/**
 * Why an image is not for this chip, or null when it is: the vector table must be exactly the chip's,
 * and, where the start-up code can be read, its stack top and EIND too (a 168's or a 1280's table is a
 * 328P's or a 2560's).
 */
export function imageMismatch(chip: Chip, bytes: Uint8Array): string | null {
  const start = readImageStart(bytes);
  const other = chipOfImage(bytes);
  const builtFor = other && other.name !== chip.name ? `This image is built for the ${other.name}` : null;
  if (start.jumps !== chip.vectors) {
    if (builtFor) return builtFor;
    if (start.jumps === 0) return `This image does not start with a vector table of jmp instructions, as every ${chip.name} image does (an ATmega8's uses rjmp; a file that is not firmware has none)`;
    return `This image starts with a vector table of ${start.jumps} jumps; the ${chip.name}'s has ${chip.vectors}`;
  }
  if (start.stackTop !== null && (start.stackTop !== chip.ramEnd || start.setsEind !== chip.threeBytePc)) {
    return builtFor ?? `This image's start-up code puts the stack at 0x${start.stackTop.toString(16)}${start.setsEind ? ' and sets EIND' : ''}; the ${chip.name}'s stack starts at 0x${chip.ramEnd.toString(16)}`;
  }
  return null;
}

export const chipBySignature = (sig: ArrayLike<number>) => CHIPS.find((c) => c.signature.every((b, i) => b === sig[i])) ?? null;

export const hexBytes = (sig: ArrayLike<number>) => Array.from(sig, (b) => b.toString(16).padStart(2, '0').toUpperCase()).join(' ');
