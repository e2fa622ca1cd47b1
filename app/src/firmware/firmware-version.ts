// After flashing: the new firmware, started by a reset, asked who it is. The Mega answers M115 once it
// has printed `start` (protocol/mega.md); the Nano answers V, S and T (protocol/nano.md).

import type { AvrBoard } from './chips';
import type { SerialLink } from './serial-link';

export interface Answered {
  /** The version line, as the firmware says it. */
  version: string;
  /** Other answers, for the record: the Nano's S and T. */
  also: string[];
}

const encode = (s: string) => Uint8Array.from(s, (c) => c.charCodeAt(0));

async function answerTo(link: SerialLink, command: string, pattern: RegExp, tries: number, everyMs: number): Promise<string | null> {
  for (let i = 0; i < tries; i++) {
    await link.write(encode(command));
    const until = Date.now() + everyMs;
    for (;;) {
      const left = until - Date.now();
      if (left <= 0) break;
      const line = await link.readLine(left);
      if (line === null) break;
      if (pattern.test(line)) return line;
    }
  }
  return null;
}

/** Asks the firmware that just started for its version; null if it never answers (about 8 s). */
export async function askVersion(link: SerialLink, board: AvrBoard): Promise<Answered | null> {
  if (board.image === 'mega') {
    // Its bootloader waits about a second, then the firmware prints `start`: bytes sent before are lost.
    for (let line = await link.readLine(6000); line !== null && line !== 'start'; line = await link.readLine(6000));
    const version = await answerTo(link, 'M115\n', /^FIRMWARE_NAME:/, 3, 1500);
    return version ? { version: version.replace(/^FIRMWARE_NAME:/, '').replace(/ PROTOCOL_VERSION.*$/, ''), also: [] } : null;
  }
  // The Nano says nothing at start: ask until it answers, past its bootloader's second.
  const identity = await answerTo(link, 'V\n', /^V:/, 16, 500);
  if (!identity) return null;
  const also: string[] = [];
  for (const [command, pattern] of [['S\n', /^S:/], ['T\n', /^T:/]] as const) {
    const line = await answerTo(link, command, pattern, 2, 500);
    if (line) also.push(line);
  }
  const [, protocol, firmware] = /^V:(\d+),(.*)$/.exec(identity) ?? [];
  return { version: firmware ? `${firmware} (Nano link protocol ${protocol})` : identity, also };
}
