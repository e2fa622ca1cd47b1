// Test-only: images laid out as avr-gcc and avr-libc's start-up code lay them out, for any chip.

const ldi = (rd: number, k: number) => 0xe000 | ((k & 0xf0) << 4) | ((rd - 16) << 4) | (k & 0x0f);
const out = (a: number, rr: number) => 0xb800 | ((a & 0x30) << 5) | (rr << 4) | (a & 0x0f);

/**
 * `vectors` jmps to the reset code right after the table; there, as avr-libc's __init does, SP set to
 * `ramEnd` (when given) and EIND set where the chip has a 22-bit program counter; then filler.
 */
export function avrImage(vectors: number, size: number, ramEnd?: number, setsEind = vectors === 57 && ramEnd === undefined): Uint8Array {
  const bytes = Uint8Array.from({ length: size }, (_, i) => (i * 31 + 7) & 0xff);
  const resetWord = vectors * 2;
  for (let v = 0; v < vectors; v++) bytes.set([0x0c, 0x94, resetWord & 0xff, resetWord >> 8], v * 4);
  const top = ramEnd ?? (vectors === 57 ? 0x21ff : 0x08ff);
  const code = [0x2411, out(0x3f, 1), ldi(28, top & 0xff), ldi(29, top >> 8), out(0x3e, 29), out(0x3d, 28)];
  if (setsEind || (ramEnd !== undefined && setsEind)) code.push(ldi(16, 0), out(0x3c, 16));
  code.push(0x0000); // nop: the end of what the check reads as start-up code
  code.forEach((w, i) => bytes.set([w & 0xff, w >> 8], vectors * 4 + i * 2));
  return bytes;
}
