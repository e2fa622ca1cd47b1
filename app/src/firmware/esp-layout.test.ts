import { describe, expect, it } from 'vitest';
import { ESP_LAYOUT, esp32Layout, espFileProblem, ownEspParts } from './esp-layout';
import { DEFAULT_CSV, partitionTable } from './esp-partitions.test-helper';

const app = (n: number) => Uint8Array.from({ length: n }, (_, i) => (i === 0 ? 0xe9 : i & 0xff));
function littlefs(n: number, at = 8): Uint8Array {
  const b = new Uint8Array(n);
  b.set(new TextEncoder().encode('littlefs'), at);
  return b;
}

describe("an ESP's own files", () => {
  it('go where PlatformIO puts them, in flash order, none overlapping the next', () => {
    expect(ESP_LAYOUT.esp8266.map((r) => [r.file, r.offset])).toEqual([['firmware.bin', 0], ['littlefs.bin', 0x200000]]);
    expect(ESP_LAYOUT.esp32.map((r) => [r.file, r.offset])).toEqual([['bootloader.bin', 0x1000], ['partitions.bin', 0x8000], ['boot_app0.bin', 0xe000], ['firmware.bin', 0x10000], ['littlefs.bin', 0x290000]]);
    for (const regions of Object.values(ESP_LAYOUT)) {
      for (let i = 1; i < regions.length; i++) expect(regions[i - 1].offset + regions[i - 1].size).toBeLessThanOrEqual(regions[i].offset);
      expect(regions.at(-1)!.offset + regions.at(-1)!.size).toBeLessThanOrEqual(4 * 1024 * 1024);
    }
  });

  it('go where the ESP32 partition table the build produced says, not where default.csv would put them', async () => {
    const moved = partitionTable([['otadata', 1, 0, 0xe000, 0x2000], ['app0', 0, 0x10, 0x10000, 0x1e0000], ['spiffs', 1, 0x82, 0x3d0000, 0x20000]]);
    const parts = await ownEspParts('esp32', { 'littlefs.bin': { name: 'fs.bin', bytes: littlefs(4096) }, 'partitions.bin': { name: 'p.bin', bytes: moved } });
    expect(parts.map((p) => [p.part.file, p.part.offset])).toEqual([['p.bin', 0x8000], ['fs.bin', 0x3d0000]]);
    expect(esp32Layout(moved).find((r) => r.file === 'firmware.bin')).toMatchObject({ offset: 0x10000, size: 0x1e0000 });
  });

  it('are refused when they are not what their place holds, or too big for it', () => {
    const [firmware, fs] = ESP_LAYOUT.esp8266;
    expect(espFileProblem(firmware, 'a.bin', app(4096))).toBeNull();
    expect(espFileProblem(firmware, 'a.bin', new Uint8Array(4096))).toMatch(/a\.bin is no ESP firmware image/);
    expect(espFileProblem(firmware, 'a.bin', app(firmware.size + 1))).toBe(`a.bin is ${firmware.size + 1} B; firmware.bin has ${firmware.size} B at 0x0`);
    expect(espFileProblem(firmware, 'a.bin', new Uint8Array(0))).toBe('a.bin is empty');
    expect(espFileProblem(fs, 'fs.bin', littlefs(8192))).toBeNull();
    expect(espFileProblem(fs, 'fs.bin', littlefs(16384, 8192 + 8))).toBeNull(); // the pair's second block holds the newer superblock
    expect(espFileProblem(fs, 'fs.bin', app(8192))).toMatch(/no LittleFS image/);
    const table = ESP_LAYOUT.esp32[1];
    expect(espFileProblem(table, 'p.bin', Uint8Array.of(0xaa, 0x50, 1))).toBeNull();
    expect(espFileProblem(table, 'p.bin', Uint8Array.of(0xe9, 0x50, 1))).toMatch(/no partition table/);
  });

  it('become the parts esptool writes, in flash order with their SHA-256, whatever order they were picked in', async () => {
    const parts = await ownEspParts('esp32', {
      'littlefs.bin': { name: 'fs.bin', bytes: littlefs(4096) }, 'firmware.bin': { name: 'hub.bin', bytes: app(16) },
      'boot_app0.bin': { name: 'boot_app0.bin', bytes: new Uint8Array(8192).fill(0xff) }, 'partitions.bin': { name: 'partitions.bin', bytes: DEFAULT_CSV },
    });
    expect(parts.map((p) => [p.part.file, p.part.offset, p.part.bytes])).toEqual([['partitions.bin', 0x8000, 3072], ['boot_app0.bin', 0xe000, 8192], ['hub.bin', 0x10000, 16], ['fs.bin', 0x290000, 4096]]);
    expect(parts[0].part.sha256).toMatch(/^[0-9a-f]{64}$/);
    await expect(ownEspParts('esp8266', {})).rejects.toThrow('Pick at least one file to flash.');
    await expect(ownEspParts('esp32', { 'firmware.bin': { name: 'hub.bin', bytes: app(16) } })).rejects.toThrow(/Pick the partitions\.bin your build produced too/);
    await expect(ownEspParts('esp32', { 'firmware.bin': { name: 'hub.bin', bytes: app(16) }, 'partitions.bin': { name: 'p.bin', bytes: Uint8Array.of(0xaa, 0x50, 0, 0) } }))
      .rejects.toThrow(/The partition table cannot be read: it holds no partitions\. Nothing was written\./);
    await expect(ownEspParts('esp32', { 'boot_app0.bin': { name: 'b.bin', bytes: new Uint8Array(4096) }, 'partitions.bin': { name: 'p.bin', bytes: DEFAULT_CSV } }))
      .rejects.toThrow(/b\.bin is 4096 B; boot_app0\.bin fills the 8192 B otadata partition at 0xe000/);
    await expect(ownEspParts('esp8266', { 'firmware.bin': { name: 'x.bin', bytes: new Uint8Array(8) } })).rejects.toThrow(/x\.bin is no ESP firmware image.*Nothing was written\./);
  });
});
