// Whether a line is the dialect's printable ASCII: what the framing and the Nano's table allow on the wire.
/** True when every byte is printable ASCII (0x20-0x7E). */
export function isPrintable(text: string): boolean {
  for (let i = 0; i < text.length; i++) {
    const c = text.charCodeAt(i);
    if (c < 0x20 || c > 0x7e) return false;
  }
  return true;
}
