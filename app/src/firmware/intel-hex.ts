// Intel HEX, as avr-objcopy and PlatformIO write it: every record's checksum checked, the data laid
// out from address 0 with the gaps left erased (0xFF), as the flash holds them.

export class HexError extends Error {}

export interface FlashImage {
  /** The bytes from address 0 to the last one the file sets; gaps are 0xFF. */
  bytes: Uint8Array;
}

/** The largest flash any board here has (the ATmega2560's): no image reaches past it. */
export const LARGEST_FLASH = 262144;

/**
 * Reads a HEX file. Every record's address is checked against `maxBytes` as it is read, before anything
 * is laid out: a record at 0xFFFF0000 is refused at once, not after allocating 4 GiB.
 */
export function parseIntelHex(text: string, maxBytes = LARGEST_FLASH): FlashImage {
  const chunks: { at: number; data: number[] }[] = [];
  let base = 0;
  let ended = false;
  let end = 0;
  const lines = text.split(/\r?\n/);
  for (let i = 0; i < lines.length && !ended; i++) {
    const line = lines[i].trim();
    if (!line) continue;
    const where = `line ${i + 1}`;
    if (!/^:([0-9A-Fa-f]{2})+$/.test(line)) throw new HexError(`${where} is not an Intel HEX record`);
    const b = Array.from({ length: (line.length - 1) / 2 }, (_, k) => parseInt(line.slice(1 + 2 * k, 3 + 2 * k), 16));
    const count = b[0];
    if (b.length !== count + 5) throw new HexError(`${where} holds ${b.length - 5} bytes but says ${count}`);
    if (b.reduce((s, x) => s + x, 0) & 0xff) throw new HexError(`${where} fails its checksum: the file is damaged`);
    const offset = (b[1] << 8) | b[2];
    const data = b.slice(4, 4 + count);
    switch (b[3]) {
      case 0:
        if (base + offset + count > maxBytes) {
          throw new HexError(`${where} puts data at 0x${(base + offset).toString(16).toUpperCase()}, past the ${maxBytes / 1024} KB of flash: this is not an image for these boards`);
        }
        chunks.push({ at: base + offset, data });
        end = Math.max(end, base + offset + count);
        break;
      case 1:
        ended = true;
        break;
      case 2:
        base = ((data[0] << 8) | data[1]) << 4;
        break;
      case 4:
        base = ((data[0] << 8) | data[1]) * 0x10000;
        break;
      // 3 and 5: start addresses, which a bootloader does not use
    }
  }
  if (!ended) throw new HexError('the file ends before its end record: it was cut short');
  if (!chunks.length) throw new HexError('the file holds no data');
  const bytes = new Uint8Array(end).fill(0xff);
  for (const c of chunks) bytes.set(c.data, c.at);
  return { bytes };
}

/** Writes an image as Intel HEX (16 bytes a record), for tests and the bench. */
export function toIntelHex(bytes: Uint8Array): string {
  const hex = (n: number) => n.toString(16).toUpperCase().padStart(2, '0');
  const record = (type: number, offset: number, data: number[]) => {
    const b = [data.length, offset >> 8, offset & 0xff, type, ...data];
    const sum = (0x100 - (b.reduce((s, x) => s + x, 0) & 0xff)) & 0xff;
    return `:${[...b, sum].map(hex).join('')}`;
  };
  const out: string[] = [];
  let segment = -1;
  for (let at = 0; at < bytes.length; at += 16) {
    if (at >> 16 !== segment) {
      segment = at >> 16;
      out.push(record(4, 0, [segment >> 8, segment & 0xff]));
    }
    out.push(record(0, at & 0xffff, Array.from(bytes.subarray(at, Math.min(at + 16, bytes.length)))));
  }
  out.push(record(1, 0, []));
  return out.join('\n') + '\n';
}
