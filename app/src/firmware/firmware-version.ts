// After flashing: the new firmware, started by a reset, asked who it is. The Mega answers M115 once it
// has printed `start` (protocol/mega.md); the Nano answers V, S and T (protocol/nano.md). A firmware that
// answers something else is reported by what it said, not as silent.

import type { AvrBoard } from './chips';

/** What asking needs of the port: SerialLink has it, and so do the tests' scripted boards. */
export interface LineLink {
  write(bytes: Uint8Array): Promise<void>;
  /** One text line without its end, or null when none ends within `timeoutMs`. */
  readLine(timeoutMs: number): Promise<string | null>;
}

export interface Answered {
  /** The version line, as the firmware says it. */
  version: string;
  /** Other answers, for the record: the Nano's S and T. */
  also: string[];
}

/** The firmware runs and spoke, but not its version: what it said, and what that means. */
export interface AnsweredOther {
  summary: string;
  lines: string[];
}

const encode = (s: string) => Uint8Array.from(s, (c) => c.charCodeAt(0));

async function answerTo(link: LineLink, heard: string[], command: string, pattern: RegExp, tries: number, everyMs: number): Promise<string | null> {
  for (let i = 0; i < tries; i++) {
    await link.write(encode(command));
    const until = Date.now() + everyMs;
    for (;;) {
      const left = until - Date.now();
      if (left <= 0) break;
      const line = await link.readLine(left);
      if (line === null) break;
      if (pattern.test(line)) return line;
      if (line.trim()) heard.push(line);
    }
  }
  return null;
}

/**
 * What the lines a firmware said instead of its version mean (codes from protocol/errors.csv). A Mega
 * halted at start is one whose stop button reads pressed: held, or wired to a pin with no pull-up.
 */
export function explainAnswer(lines: string[]): AnsweredOther {
  const halted = lines.find((l) => /\bE13\b|stop button: halted/.test(l));
  if (halted) return { summary: 'halted: E13 — release the stop button, then send M999 (or reset the board)', lines };
  const coded = lines.find((l) => /\bE\d+\b/.test(l));
  return { summary: `it answered "${coded ?? lines[lines.length - 1]}"`, lines };
}

/** Asks the firmware that just started for its version; what it said otherwise; null if it said nothing (about 8 s). */
export async function askVersion(link: LineLink, board: AvrBoard): Promise<Answered | AnsweredOther | null> {
  const heard: string[] = [];
  if (board.image === 'mega') {
    // Its bootloader waits about a second, then the firmware prints `start`: bytes sent before are lost.
    for (let line = await link.readLine(6000); line !== null && line !== 'start'; line = await link.readLine(6000)) if (line.trim()) heard.push(line);
    const version = await answerTo(link, heard, 'M115\n', /^FIRMWARE_NAME:/, 3, 1500);
    if (version) return { version: version.replace(/^FIRMWARE_NAME:/, '').replace(/ PROTOCOL_VERSION.*$/, ''), also: [] };
    return heard.length ? explainAnswer(heard) : null;
  }
  // The Nano says nothing at start: ask until it answers, past its bootloader's second.
  const identity = await answerTo(link, heard, 'V\n', /^V:/, 16, 500);
  if (!identity) return heard.length ? explainAnswer(heard) : null;
  const also: string[] = [];
  for (const [command, pattern] of [['S\n', /^S:/], ['T\n', /^T:/]] as const) {
    const line = await answerTo(link, [], command, pattern, 2, 500);
    if (line) also.push(line);
  }
  const [, protocol, firmware] = /^V:(\d+),(.*)$/.exec(identity) ?? [];
  return { version: firmware ? `${firmware} (Nano link protocol ${protocol})` : identity, also };
}
