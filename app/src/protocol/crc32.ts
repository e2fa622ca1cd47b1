// CRC-32 (IEEE 802.3, reflected, as zlib) over Latin-1 text: the whole-job hash of protocol/job.md.

const TABLE = (() => {
  const t = new Uint32Array(256);
  for (let i = 0; i < 256; i++) {
    let c = i;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    t[i] = c >>> 0;
  }
  return t;
})();

/** Running CRC: start with `crc32Update(0, ...)`, feed more text with the previous result. */
export function crc32Update(crc: number, text: string): number {
  let c = ~crc >>> 0;
  for (let i = 0; i < text.length; i++) c = TABLE[(c ^ text.charCodeAt(i)) & 0xff] ^ (c >>> 8);
  return ~c >>> 0;
}

export function crc32Hex(crc: number): string {
  return crc.toString(16).padStart(8, '0');
}
