// An ESP32 partition table as the build wrote it (partitions.bin, flashed at 0x8000): where the app,
// the otadata that boot_app0.bin initialises, and the LittleFS image go. The ESP-IDF format: 32-byte
// entries, magic 0xAA 0x50, type, subtype, offset and size (little endian), a 16-byte label, flags;
// an MD5 entry (0xEB 0xEB) or erased bytes end it.

export interface Partition {
  type: number;
  subtype: number;
  offset: number;
  size: number;
  label: string;
}

export class PartitionTableError extends Error {}

export function parsePartitionTable(bytes: Uint8Array): Partition[] {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const partitions: Partition[] = [];
  for (let at = 0; at + 32 <= bytes.length; at += 32) {
    if (bytes[at] === 0xeb && bytes[at + 1] === 0xeb) break; // the table's MD5
    if (bytes[at] === 0xff && bytes[at + 1] === 0xff) break; // erased: the end
    if (bytes[at] !== 0xaa || bytes[at + 1] !== 0x50) throw new PartitionTableError(`entry ${partitions.length + 1} does not begin with 0xAA 0x50`);
    const label = new TextDecoder().decode(bytes.subarray(at + 12, at + 28)).replace(/\0.*$/s, '');
    partitions.push({ type: bytes[at + 2], subtype: bytes[at + 3], offset: view.getUint32(at + 4, true), size: view.getUint32(at + 8, true), label });
  }
  if (!partitions.length) throw new PartitionTableError('it holds no partitions');
  return partitions;
}

/** Where an ESP32's own files go, by the table: what esptool's flash arguments say for these files. */
export interface Esp32Places {
  'firmware.bin': { offset: number; size: number };
  'littlefs.bin': { offset: number; size: number };
  'boot_app0.bin': { offset: number; size: number };
}

const APP = 0x00;
const DATA = 0x01;

export function esp32Places(partitions: Partition[]): Esp32Places {
  // The app the bootloader starts with erased otadata: factory if there is one, else ota_0 (app0).
  const app = partitions.find((p) => p.type === APP && p.subtype === 0x00) ?? partitions.find((p) => p.type === APP && p.subtype === 0x10);
  const otadata = partitions.find((p) => p.type === DATA && p.subtype === 0x00);
  // LittleFS sits in a "spiffs" (0x82) or "littlefs" (0x83) data partition.
  const fs = partitions.find((p) => p.type === DATA && (p.subtype === 0x82 || p.subtype === 0x83));
  const missing = [!app && 'an app partition', !otadata && 'an otadata partition', !fs && 'a spiffs or littlefs partition'].filter(Boolean);
  if (missing.length) throw new PartitionTableError(`it lacks ${missing.join(' and ')}`);
  const place = (p: Partition) => ({ offset: p.offset, size: p.size });
  return { 'firmware.bin': place(app!), 'littlefs.bin': place(fs!), 'boot_app0.bin': place(otadata!) };
}
