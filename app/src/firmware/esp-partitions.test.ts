import { describe, expect, it } from 'vitest';
import { esp32Places, parsePartitionTable, PartitionTableError } from './esp-partitions';
import { DEFAULT_CSV, partitionTable } from './esp-partitions.test-helper';

describe('an ESP32 partition table', () => {
  it('gives the offsets the build chose: app0, otadata for boot_app0.bin, the filesystem', () => {
    const table = parsePartitionTable(DEFAULT_CSV);
    expect(table.map((p) => p.label)).toEqual(['nvs', 'otadata', 'app0', 'app1', 'spiffs']);
    expect(esp32Places(table)).toEqual({
      'firmware.bin': { offset: 0x10000, size: 0x140000 },
      'littlefs.bin': { offset: 0x290000, size: 0x160000 },
      'boot_app0.bin': { offset: 0xe000, size: 0x2000 },
    });
  });

  it('follows another layout (min_spiffs.csv: larger apps, a smaller filesystem)', () => {
    const table = parsePartitionTable(partitionTable([
      ['nvs', 1, 0x02, 0x9000, 0x5000], ['otadata', 1, 0x00, 0xe000, 0x2000], ['app0', 0, 0x10, 0x10000, 0x1e0000],
      ['app1', 0, 0x11, 0x1f0000, 0x1e0000], ['spiffs', 1, 0x82, 0x3d0000, 0x20000],
    ]));
    expect(esp32Places(table)['littlefs.bin']).toEqual({ offset: 0x3d0000, size: 0x20000 });
  });

  it.each([
    ['no magic', Uint8Array.of(...new Array(32).fill(0x12)), /entry 1 does not begin with 0xAA 0x50/],
    ['nothing in it', new Uint8Array(64).fill(0xff), /holds no partitions/],
  ])('is refused with %s', (_, bytes, message) => {
    expect(() => parsePartitionTable(bytes)).toThrow(PartitionTableError);
    expect(() => parsePartitionTable(bytes)).toThrow(message);
  });

  it('is refused when it lacks a place for one of the files', () => {
    const table = parsePartitionTable(partitionTable([['app0', 0, 0x10, 0x10000, 0x140000]]));
    expect(() => esp32Places(table)).toThrow('it lacks an otadata partition and a spiffs or littlefs partition');
  });
});
