// Test-only: ESP32 partition tables as PlatformIO's build writes them.

/** A partitions.bin as gen_esp32part.py writes one from rows of a CSV. */
export function partitionTable(rows: [string, number, number, number, number][]): Uint8Array {
  const bytes = new Uint8Array(3072).fill(0xff);
  const view = new DataView(bytes.buffer);
  rows.forEach(([label, type, subtype, offset, size], i) => {
    const at = i * 32;
    bytes.set([0xaa, 0x50, type, subtype], at);
    view.setUint32(at + 4, offset, true);
    view.setUint32(at + 8, size, true);
    bytes.fill(0, at + 12, at + 32);
    bytes.set(new TextEncoder().encode(label), at + 12);
  });
  bytes.set([0xeb, 0xeb], rows.length * 32); // the MD5 entry
  return bytes;
}

/** Arduino-ESP32's default.csv, as PlatformIO builds it. */
export const DEFAULT_CSV = partitionTable([
  ['nvs', 1, 0x02, 0x9000, 0x5000],
  ['otadata', 1, 0x00, 0xe000, 0x2000],
  ['app0', 0, 0x10, 0x10000, 0x140000],
  ['app1', 0, 0x11, 0x150000, 0x140000],
  ['spiffs', 1, 0x82, 0x290000, 0x160000],
]);
