import { createHash } from 'node:crypto';
import { describe, expect, it } from 'vitest';
import { flashEsp, type EspLibrary, type EspLoader } from './esp-flash';
import { FlashError, type FlashProgress } from './flash-avr';

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
        // As esptool-js: compressed bytes sent of the compressed size (here a third of the file's).
        const compressed = Math.ceil(f.data.length / 3);
        for (const sent of [0, Math.ceil(compressed / 2), compressed]) o.reportProgress?.(i, sent, compressed);
      }
    },
    async flashMd5sum(address, size) {
      calls.push(`md5 0x${address.toString(16)}:${size}`);
      return createHash('md5').update(flash.subarray(address, address + size)).digest('hex');
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
  it('hands the firmware and the LittleFS image to the library at their offsets, checks each by the ESP\'s MD5, and resets', async () => {
    const esp = fakeLibrary('ESP8266');
    const parts = [part('esp8266-firmware.bin', 0, 4000), part('esp8266-littlefs.bin', 0x200000, 3000)];
    const seen: FlashProgress[] = [];
    await flashEsp({} as SerialPort, 'esp8266', parts, (p) => seen.push(p), esp.library);
    expect(esp.calls).toEqual(['open 460800', 'main', 'write 0x0:4000 0x200000:3000 compress=true erase=false size=keep', 'md5 0x0:4000', 'md5 0x200000:3000', 'after hard_reset', 'close']);
    expect(esp.flash.subarray(0x200000, 0x200000 + 3000)).toEqual(parts[1].data);
    // An honest bar: the file's own bytes, in step with the compressed ones sent, never past the total.
    const writing = seen.flatMap((p) => (p.phase === 'writing' ? [p.done] : []));
    expect(writing).toEqual([0, 2000, 4000, 4000, 5500, 7000]);
    expect(seen.at(-1)).toEqual({ phase: 'verifying', done: 7000, total: 7000 });
  });

  it('says which region differs when the ESP\'s MD5 is not the file\'s', async () => {
    const esp = fakeLibrary('ESP8266');
    const write = esp.library.open;
    esp.library = { open: async (port, baud) => {
      const session = await write(port, baud);
      const md5 = session.loader.flashMd5sum.bind(session.loader);
      session.loader.flashMd5sum = async (a, n) => (a === 0x200000 ? '0'.repeat(32) : md5(a, n));
      return session;
    } };
    const e = await flashEsp({} as SerialPort, 'esp8266', [part('a.bin', 0, 100), part('b.bin', 0x200000, 100)], () => {}, esp.library).catch((x) => x);
    expect(e.failure).toBe('verify-failed');
    expect(e.message).toMatch(/^The flash at 0x200000 does not hold b\.bin/);
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
