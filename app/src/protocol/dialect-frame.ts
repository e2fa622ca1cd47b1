// Line framing of the Mega dialect as the app writes it: `N<n> <body>*<cs>#<crc>` (protocol/mega.md §1).
// The Mega reads the frames (firmware/common/protocol/src/dialect_frame.*).

import { crc16Hex } from './crc16';

export const DIALECT_MAX_LINE = 96;

/** Marlin's check: the XOR of every byte before the `*`. */
function xorChecksum(text: string): number {
  let x = 0;
  for (let i = 0; i < text.length; i++) x ^= text.charCodeAt(i) & 0xff;
  return x;
}

/** `N<n> <body>*<cs>#<crc>` without a newline. */
export function encodeFrame(n: number, body: string): string {
  const head = `N${n} ${body}`;
  return `${head}*${xorChecksum(head)}#${crc16Hex(head)}`;
}
