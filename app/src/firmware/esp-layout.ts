// Where each of an ESP's files goes in its flash, how much room it has there, and what its first bytes
// must be, as firmware/esp/platformio.ini builds them: the ESP8266 with eagle.flash.4m2m.ld (the
// sketch's 1 MB at 0, LittleFS from 0x200000 to 0x3FA000), the ESP32 with default.csv (its
// second-stage bootloader at 0x1000, the partition table at 0x8000, app0 at 0x10000 with 0x140000,
// LittleFS at 0x290000 with 0x160000). esp-layout.json holds the numbers, which
// scripts/firmware-manifest.mjs reads too for the published images.

import layout from './esp-layout.json';
import type { EspBoard, EspPart } from './esp-flash';

export interface EspRegion {
  file: string;
  offset: number;
  size: number;
  /** app: an ESP image (0xE9 first); partitions: a partition table (0xAA 0x50 first); littlefs: "littlefs" in its superblock. */
  kind: 'app' | 'partitions' | 'littlefs';
}

export const ESP_LAYOUT = layout as Record<EspBoard, EspRegion[]>;

const hex = (n: number) => `0x${n.toString(16)}`;

/** Why `bytes` cannot be the board's `region`, or null when it can. */
export function espFileProblem(region: EspRegion, name: string, bytes: Uint8Array): string | null {
  if (!bytes.length) return `${name} is empty`;
  if (bytes.length > region.size) return `${name} is ${bytes.length} B; ${region.file} has ${region.size} B at ${hex(region.offset)}`;
  if (region.kind === 'app' && bytes[0] !== 0xe9) return `${name} is no ESP firmware image (those begin with the byte 0xE9): is it the ${region.file} PlatformIO built for this board?`;
  if (region.kind === 'partitions' && (bytes[0] !== 0xaa || bytes[1] !== 0x50)) return `${name} is no partition table (those begin with 0xAA 0x50)`;
  if (region.kind === 'littlefs') {
    // The superblock's name tag holds "littlefs" 8 bytes into either block of its pair (4 or 8 KB blocks).
    const at = (k: number) => new TextDecoder().decode(bytes.subarray(k, k + 8)) === 'littlefs';
    if (![8, 4096 + 8, 8192 + 8].some(at)) return `${name} is no LittleFS image (npm run build:esp and pio run -t buildfs make one)`;
  }
  return null;
}

/** The files a person picked, checked and in flash order, each with its SHA-256; throws what is wrong. */
export async function ownEspParts(board: EspBoard, picked: Partial<Record<string, { name: string; bytes: Uint8Array }>>): Promise<EspPart[]> {
  const parts: EspPart[] = [];
  for (const region of ESP_LAYOUT[board]) {
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
