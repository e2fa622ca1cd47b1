// Where each of an ESP's files goes in its flash, how much room it has there, and what its first bytes
// must be, as firmware/esp/platformio.ini builds them: the ESP8266 with eagle.flash.4m2m.ld (the
// sketch's 1 MB at 0, LittleFS from 0x200000 to 0x3FA000), the ESP32 with default.csv (its
// second-stage bootloader at 0x1000, the partition table at 0x8000, boot_app0.bin in otadata at 0xE000,
// app0 at 0x10000 with 0x140000, LittleFS at 0x290000 with 0x160000). esp-layout.json holds the
// numbers. The ESP32's are default.csv's, shown before a table is picked: its files go where the
// partitions.bin the build produced says (esp-partitions.ts), here and in scripts/firmware-manifest.mjs.

import layout from './esp-layout.json';
import type { EspBoard, EspPart } from './esp-flash';
import { esp32Places, parsePartitionTable, type Esp32Places } from './esp-partitions';

export interface EspRegion {
  file: string;
  offset: number;
  size: number;
  /** app: an ESP image (0xE9 first); partitions: a partition table (0xAA 0x50 first); littlefs: "littlefs" in its superblock; otadata: boot_app0.bin, the otadata partition whole. */
  kind: 'app' | 'partitions' | 'littlefs' | 'otadata';
}

export const ESP_LAYOUT = layout as Record<EspBoard, EspRegion[]>;

const hex = (n: number) => `0x${n.toString(16)}`;

/** Why `bytes` cannot be the board's `region`, or null when it can. */
export function espFileProblem(region: EspRegion, name: string, bytes: Uint8Array): string | null {
  if (!bytes.length) return `${name} is empty`;
  if (bytes.length > region.size) return `${name} is ${bytes.length} B; ${region.file} has ${region.size} B at ${hex(region.offset)}`;
  if (region.kind === 'app' && bytes[0] !== 0xe9) return `${name} is no ESP firmware image (those begin with the byte 0xE9): is it the ${region.file} PlatformIO built for this board?`;
  if (region.kind === 'partitions' && (bytes[0] !== 0xaa || bytes[1] !== 0x50)) return `${name} is no partition table (those begin with 0xAA 0x50)`;
  if (region.kind === 'otadata' && bytes.length !== region.size) return `${name} is ${bytes.length} B; boot_app0.bin fills the ${region.size} B otadata partition at ${hex(region.offset)}`;
  if (region.kind === 'littlefs') {
    // The superblock's name tag holds "littlefs" 8 bytes into either block of its pair (4 or 8 KB blocks).
    const at = (k: number) => new TextDecoder().decode(bytes.subarray(k, k + 8)) === 'littlefs';
    if (![8, 4096 + 8, 8192 + 8].some(at)) return `${name} is no LittleFS image (npm run build:esp and pio run -t buildfs make one)`;
  }
  return null;
}

/** The files a person picked, checked and in flash order, each with its SHA-256; throws what is wrong. */
/**
 * The ESP32's regions as its partition table places them: app0, otadata and the filesystem where the
 * table says, the bootloader and the table itself where the ROM and the bootloader look.
 */
export function esp32Layout(table: Uint8Array): EspRegion[] {
  let places: Esp32Places;
  try {
    places = esp32Places(parsePartitionTable(table));
  } catch (e) {
    throw new Error(`The partition table cannot be read: ${(e as Error).message}. Nothing was written.`);
  }
  return ESP_LAYOUT.esp32.map((r) => (r.file in places ? { ...r, ...places[r.file as keyof Esp32Places] } : r));
}

export async function ownEspParts(board: EspBoard, picked: Partial<Record<string, { name: string; bytes: Uint8Array }>>): Promise<EspPart[]> {
  const parts: EspPart[] = [];
  let layout = ESP_LAYOUT[board];
  if (board === 'esp32' && ['firmware.bin', 'littlefs.bin', 'boot_app0.bin'].some((f) => picked[f])) {
    const table = picked['partitions.bin'];
    if (!table) throw new Error('Pick the partitions.bin your build produced too (PlatformIO: .pio/build/esp32dev/partitions.bin): the ESP32\'s offsets come from it. Nothing was written.');
    layout = esp32Layout(table.bytes);
  }
  for (const region of layout) {
    const own = picked[region.file];
    if (!own) continue;
    const problem = espFileProblem(region, own.name, own.bytes);
    if (problem) throw new Error(`${problem}. Nothing was written.`);
    const digest = new Uint8Array(await crypto.subtle.digest('SHA-256', own.bytes as Uint8Array<ArrayBuffer>));
    const sha256 = Array.from(digest, (b) => b.toString(16).padStart(2, '0')).join('');
    parts.push({ part: { file: own.name, offset: region.offset, sha256, bytes: own.bytes.length }, data: own.bytes });
  }
  if (!parts.length) throw new Error('Pick at least one file to flash.');
  return parts;
}
