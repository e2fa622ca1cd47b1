import { describe, expect, it } from 'vitest';
import { flashEsp, type EspLibrary, type EspLoader } from './esp-flash';
import { FlashError } from './flash-avr';

/** esptool-js's loader, faked: a flash in memory behind the calls the hand-off makes. */
function fakeLibrary(chipName: string) {
  const flash = new Uint8Array(0x400000).fill(0xff);
  const calls: string[] = [];
  const loader: EspLoader = {
    chip: { CHIP_NAME: chipName },
    async main() {
      calls.push('main');
      return `${chipName}EX`;
    },
    async writeFlash(o) {
      calls.push(`write ${o.fileArray.map((f) => `0x${f.address.toString(16)}:${f.data.length}`).join(' ')} compress=${o.compress} erase=${o.eraseAll} size=${o.flashSize}`);
      for (const [i, f] of o.fileArray.entries()) {
        flash.set(f.data, f.address);
        o.reportProgress?.(i, f.data.length, f.data.length);
      }
    },
    async readFlash(address, size) {
      calls.push(`read 0x${address.toString(16)}:${size}`);
      return flash.slice(address, address + size);
    },
    async after(mode) {
      calls.push(`after ${mode}`);
    },
  };
  const library: EspLibrary = { open: async (_port, baud) => (calls.push(`open ${baud}`), { loader, close: async () => void calls.push('close') }) };
  return { flash, calls, library };
}

const part = (file: string, offset: number, size: number) => ({
  part: { file, offset, sha256: '0'.repeat(64), bytes: size },
  data: Uint8Array.from({ length: size }, (_, i) => (i * 13 + offset) & 0xff),
});

describe('flashing the ESP through esptool-js', () => {
  it('hands the firmware and the LittleFS image to the library at their offsets, reads both back, and resets', async () => {
    const esp = fakeLibrary('ESP8266');
    const parts = [part('esp8266-firmware.bin', 0, 4000), part('esp8266-littlefs.bin', 0x200000, 3000)];
    const phases: string[] = [];
    await flashEsp({} as SerialPort, 'esp8266', parts, (p) => phases.push(p.phase), esp.library);
    expect(esp.calls).toEqual(['open 460800', 'main', 'write 0x0:4000 0x200000:3000 compress=true erase=false size=keep', 'read 0x0:4000', 'read 0x200000:3000', 'after hard_reset', 'close']);
    expect(esp.flash.subarray(0x200000, 0x200000 + 3000)).toEqual(parts[1].data);
    expect(phases).toContain('verifying');
  });

  it('refuses an ESP32 where an ESP8266 was picked, before writing', async () => {
    const esp = fakeLibrary('ESP32');
    const e = await flashEsp({} as SerialPort, 'esp8266', [part('f.bin', 0, 10)], () => {}, esp.library).catch((x) => x);
    expect(e).toBeInstanceOf(FlashError);
    expect(e.message).toContain('has an ESP32, not an ESP8266');
    expect(esp.calls.some((c) => c.startsWith('write'))).toBe(false);
    expect(esp.calls.at(-1)).toBe('close');
  });

  it('says how to enter the ROM bootloader when nothing answers', async () => {
    const esp = fakeLibrary('ESP8266');
    esp.library = { open: async () => ({ loader: { chip: { CHIP_NAME: '' }, main: () => Promise.reject(new Error('Failed to connect with the device')) } as unknown as EspLoader, close: async () => {} }) };
    const e = await flashEsp({} as SerialPort, 'esp8266', [part('f.bin', 0, 10)], () => {}, esp.library).catch((x) => x);
    expect(e.failure).toBe('no-bootloader');
    expect(e.message).toContain('5, 6 and 7 ON');
  });
});
