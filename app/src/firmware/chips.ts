// The boards the app flashes, the chips on them and their bootloaders: where each image may go.

export interface Chip {
  name: string;
  /** The signature bytes the chip answers (its datasheet's "Signature Bytes"). */
  signature: [number, number, number];
  flashBytes: number;
  /** The flash page: the unit the bootloader erases and writes. */
  pageBytes: number;
  /** Interrupt vectors, each a 4-byte jmp: how the start of an image says which chip it was built for. */
  vectors: number;
}

export const ATMEGA328P: Chip = { name: 'ATmega328P', signature: [0x1e, 0x95, 0x0f], flashBytes: 32768, pageBytes: 128, vectors: 26 };
export const ATMEGA2560: Chip = { name: 'ATmega2560', signature: [0x1e, 0x98, 0x01], flashBytes: 262144, pageBytes: 256, vectors: 57 };
export const CHIPS = [ATMEGA328P, ATMEGA2560];

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
  /** The boot section the bootloader keeps at the end of flash. */
  bootBytes: number;
  /** How to plug it in, said before the port is picked. */
  plugIn: string;
  /** The firmware's own baud, for asking it its version afterwards. */
  firmwareBaud: number;
}

export const AVR_BOARDS: AvrBoard[] = [
  {
    id: 'nano', image: 'nano', name: 'Nano (printhead), Optiboot', chip: ATMEGA328P, protocol: 'stk500v1', baud: 115200, bootBytes: 512, firmwareBaud: 115200,
    plugIn: 'Unplug the Nano from the Mega (its TX and RX must be free), then plug the Nano into this computer by its USB port.',
  },
  {
    id: 'nano-old', image: 'nano', name: 'Nano (printhead), old bootloader', chip: ATMEGA328P, protocol: 'stk500v1', baud: 57600, bootBytes: 2048, firmwareBaud: 115200,
    plugIn: 'Unplug the Nano from the Mega (its TX and RX must be free), then plug the Nano into this computer by its USB port. Nanos sold before 2018 (and many clones) have this bootloader.',
  },
  {
    id: 'mega', image: 'mega', name: 'Mega 2560 (motion controller)', chip: ATMEGA2560, protocol: 'stk500v2', baud: 115200, bootBytes: 8192, firmwareBaud: 115200,
    plugIn: 'Plug the Mega into this computer by its USB port. On a Mega+WiFi board, set DIP switches 3 and 4 ON and the others OFF (USB to the ATmega2560).',
  },
];

export const flashLimit = (b: AvrBoard) => b.chip.flashBytes - b.bootBytes;

/** The chip an image was built for, by its vector table; null when the start is not a vector table. */
export function chipOfImage(bytes: Uint8Array): Chip | null {
  let jumps = 0;
  while (jumps * 4 + 1 < bytes.length && bytes[jumps * 4] === 0x0c && bytes[jumps * 4 + 1] === 0x94) jumps++;
  // The most vectors the image has, of the chips we know: a 2560 image's table also starts like a 328P's.
  const fits = CHIPS.filter((c) => jumps >= c.vectors).sort((a, b) => b.vectors - a.vectors);
  return fits[0] ?? null;
}

export const chipBySignature = (sig: ArrayLike<number>) => CHIPS.find((c) => c.signature.every((b, i) => b === sig[i])) ?? null;

export const hexBytes = (sig: ArrayLike<number>) => Array.from(sig, (b) => b.toString(16).padStart(2, '0').toUpperCase()).join(' ');
