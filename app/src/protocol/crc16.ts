// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF): the strong line check of protocol/mega.md §1.

export function crc16(text: string): number {
  let c = 0xffff;
  for (let i = 0; i < text.length; i++) {
    c ^= (text.charCodeAt(i) & 0xff) << 8;
    for (let k = 0; k < 8; k++) c = c & 0x8000 ? ((c << 1) ^ 0x1021) & 0xffff : (c << 1) & 0xffff;
  }
  return c;
}

export function crc16Hex(text: string): string {
  return crc16(text).toString(16).padStart(4, '0');
}
