// Flashing the ESP8266 or ESP32 (the Wi-Fi hub) through Espressif's esptool-js: its ROM bootloader's
// SLIP protocol, the stub flasher and compressed writes are the library's; this file picks the files
// and their offsets from the manifest, refuses the other ESP chip, checks every region by the MD5 the
// ESP computes of its flash (as esptool and esp-web-tools do, not by reading it all back), and resets.
// esptool-js loads only when an ESP is flashed (its own chunk).

import { FlashError, type FlashProgress } from './flash-avr';
import type { ImagePart } from './manifest';
import { md5Hex } from './md5';

/** The part of esptool-js's ESPLoader used here (a fake in the tests). */
export interface EspLoader {
  chip: { CHIP_NAME: string };
  main(): Promise<string>;
  writeFlash(options: { fileArray: { data: Uint8Array; address: number }[]; flashMode: 'keep'; flashFreq: 'keep'; flashSize: 'keep'; eraseAll: boolean; compress: boolean; reportProgress?: (file: number, written: number, total: number) => void }): Promise<void>;
  /** SPI_FLASH_MD5: the ROM's or the stub's MD5 of a flash region, as hex. */
  flashMd5sum(address: number, size: number): Promise<string>;
  after(mode?: 'hard_reset'): Promise<void>;
}

export interface EspLibrary {
  /** A loader over the port, at `baudrate` once its stub runs; `close` lets the port go. */
  open(port: SerialPort, baudrate: number): Promise<{ loader: EspLoader; close(): Promise<void> }>;
}

/** esptool-js itself, over the port (its Transport opens it at the ROM's 115200). */
export const esptoolJs: EspLibrary = {
  async open(port, baudrate) {
    const { ESPLoader, Transport } = await import('esptool-js');
    const transport = new Transport(port, false);
    const loader = new ESPLoader({ transport, baudrate, romBaudrate: 115200, debugLogging: false });
    return { loader: loader as unknown as EspLoader, close: () => transport.disconnect() };
  },
};

export type EspBoard = 'esp8266' | 'esp32';
const CHIP_NAMES: Record<EspBoard, string> = { esp8266: 'ESP8266', esp32: 'ESP32' };

export interface EspPart {
  part: ImagePart;
  data: Uint8Array;
}

/** Writes every file at its offset, reads each back, and starts the new firmware. Returns the chip's description. */
export async function flashEsp(port: SerialPort, board: EspBoard, parts: EspPart[], progress: (p: FlashProgress) => void = () => {}, library: EspLibrary = esptoolJs): Promise<string> {
  progress({ phase: 'connecting' });
  let session: Awaited<ReturnType<EspLibrary['open']>> | null = null;
  try {
    session = await library.open(port, 460800);
    const { loader } = session;
    let description: string;
    try {
      description = await loader.main();
    } catch (e) {
      throw new FlashError('no-bootloader', `No ESP bootloader answered (${(e as Error).message}). Set the DIP switches for flashing the ESP (5, 6 and 7 ON, the others OFF), plug the board in again and retry; on a bare ESP board, hold BOOT (GPIO0 low) while pressing RESET.`);
    }
    if (loader.chip.CHIP_NAME !== CHIP_NAMES[board]) {
      throw new FlashError('wrong-chip', `The board on this port has an ${loader.chip.CHIP_NAME}, not an ${CHIP_NAMES[board]}. Nothing was written. Pick the board that is plugged in.`);
    }
    const total = parts.reduce((n, p) => n + p.data.length, 0);
    const before = (i: number) => parts.slice(0, i).reduce((n, p) => n + p.data.length, 0);
    await loader.writeFlash({
      fileArray: parts.map((p) => ({ data: p.data, address: p.part.offset })),
      flashMode: 'keep', flashFreq: 'keep', flashSize: 'keep', eraseAll: false, compress: true,
      // esptool-js counts a file's compressed bytes sent of its compressed size: that fraction of the
      // file's own size is what the bar adds, in the same unit as its total.
      reportProgress: (file, sent, compressed) => progress({ phase: 'writing', done: before(file) + Math.round((parts[file].data.length * sent) / Math.max(compressed, 1)), total }),
    });
    progress({ phase: 'verifying', done: 0, total });
    for (const [i, p] of parts.entries()) {
      const onChip = await loader.flashMd5sum(p.part.offset, p.data.length);
      if (onChip.toLowerCase() !== md5Hex(p.data)) {
        throw new FlashError('verify-failed', `The flash at 0x${p.part.offset.toString(16)} does not hold ${p.part.file} (its MD5 is ${onChip}, the file's ${md5Hex(p.data)}). The ESP's ROM bootloader cannot be overwritten: flash again.`);
      }
      progress({ phase: 'verifying', done: before(i + 1), total });
    }
    await loader.after('hard_reset');
    return description;
  } catch (e) {
    if (e instanceof FlashError) throw e;
    throw new FlashError('cable-pulled', `The ESP stopped answering (${(e as Error).message}): the cable was pulled, or the board lost power. Its bootloader is in ROM and cannot be harmed: plug it in again and flash again.`);
  } finally {
    await session?.close().catch(() => {});
  }
}
