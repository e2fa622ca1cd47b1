// Flashing the ESP8266 or ESP32 (the Wi-Fi hub) through Espressif's esptool-js: its ROM bootloader's
// SLIP protocol, the stub flasher and compressed writes are the library's; this file picks the files
// and their offsets from the manifest, refuses the other ESP chip, reads every file back, and resets.
// esptool-js loads only when an ESP is flashed (its own chunk).

import { FlashError, type FlashProgress } from './flash-avr';
import type { ImagePart } from './manifest';

/** The part of esptool-js's ESPLoader used here (a fake in the tests). */
export interface EspLoader {
  chip: { CHIP_NAME: string };
  main(): Promise<string>;
  writeFlash(options: { fileArray: { data: Uint8Array; address: number }[]; flashMode: 'keep'; flashFreq: 'keep'; flashSize: 'keep'; eraseAll: boolean; compress: boolean; reportProgress?: (file: number, written: number, total: number) => void }): Promise<void>;
  readFlash(address: number, size: number): Promise<Uint8Array>;
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
      reportProgress: (file, written) => progress({ phase: 'writing', done: before(file) + written, total }),
    });
    for (const [i, p] of parts.entries()) {
      const back = await loader.readFlash(p.part.offset, p.data.length);
      const at = p.data.findIndex((b, k) => back[k] !== b);
      if (at >= 0 || back.length < p.data.length) {
        throw new FlashError('verify-failed', `Reading ${p.part.file} back, byte 0x${(p.part.offset + Math.max(at, 0)).toString(16)} differs. The ESP's ROM bootloader cannot be overwritten: flash again.`);
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
