// STK500 v2 (Atmel AVR068) framing and the commands the Mega 2560's wiring bootloader (stk500boot.c)
// answers: sign-on, signature, and flash written and read a page at a time.
//
// Written here rather than taken from npm: the `stk500-v2` package (1.0.4) drives a Node serialport
// stream with Node's Buffer and callbacks (async 0.9), and has nothing for Web Serial.

import { LinkTimeout, type ByteLink } from './byte-link';
import { ProtocolError } from './stk500v1';

const MESSAGE_START = 0x1b;
const TOKEN = 0x0e;
const CMD = { SIGN_ON: 0x01, LOAD_ADDRESS: 0x06, ENTER_PROGMODE_ISP: 0x10, LEAVE_PROGMODE_ISP: 0x11, PROGRAM_FLASH_ISP: 0x13, READ_FLASH_ISP: 0x14, READ_SIGNATURE_ISP: 0x1b } as const;
const STATUS_CMD_OK = 0x00;

/** One message on the wire: start, sequence, size, token, body, XOR of all before. */
export function frame(sequence: number, body: ArrayLike<number>): Uint8Array {
  const out = [MESSAGE_START, sequence & 0xff, body.length >> 8, body.length & 0xff, TOKEN, ...Array.from(body)];
  out.push(out.reduce((x, b) => x ^ b, 0));
  return Uint8Array.from(out);
}

export class Stk500v2 {
  #sequence = 0;
  /** Where the bootloader's address points: it moves on past each page written or read. */
  #next = -1;

  /** `timeoutMs`: how long an answer may take, avrdude's for STK500 v2 (stk500v2.c's SERIAL_TIMEOUT, 2 s). */
  constructor(private readonly link: ByteLink, private readonly timeoutMs = 2000) {}

  /**
   * The bootloader's name: "AVRISP_2" for the Mega's. Asked again and again for `withinMs`, as avrdude
   * does: a chip still in its start-up time-out drops the first, and a late answer to an earlier one,
   * or line noise, is skipped.
   */
  async signOn(withinMs = 1500): Promise<string> {
    const until = Date.now() + withinMs;
    for (;;) {
      try {
        const answer = await this.#command([CMD.SIGN_ON], Math.min(this.timeoutMs, 300));
        return String.fromCharCode(...answer.subarray(3, 3 + answer[2]));
      } catch (e) {
        if (!(e instanceof LinkTimeout || e instanceof ProtocolError) || Date.now() >= until) throw e;
        this.link.discard();
      }
    }
  }

  async signature(): Promise<Uint8Array> {
    const sig = new Uint8Array(3);
    for (let i = 0; i < 3; i++) sig[i] = (await this.#command([CMD.READ_SIGNATURE_ISP, 0x04, 0x30, 0x00, i, 0x00]))[2];
    return sig;
  }

  async enterProgramming(): Promise<void> {
    // The timings avrdude sends for the ATmega2560; the bootloader ignores them.
    await this.#command([CMD.ENTER_PROGMODE_ISP, 0xc8, 0x64, 0x19, 0x20, 0x00, 0x53, 0x03, 0xac, 0x53, 0x00, 0x00]);
  }

  async leaveProgramming(): Promise<void> {
    await this.#command([CMD.LEAVE_PROGMODE_ISP, 0x01, 0x01]);
  }

  /**
   * Writes one page. stk500boot.c erases the next page of its own count (from 0) at every write, not
   * the page addressed: pages must come in order from address 0, none skipped (FlashSession does).
   */
  async writePage(byteAddress: number, page: Uint8Array): Promise<void> {
    await this.#loadAddress(byteAddress, page.length);
    await this.#command([CMD.PROGRAM_FLASH_ISP, page.length >> 8, page.length & 0xff, 0xc1, 0x0a, 0x40, 0x4c, 0x20, 0x00, 0x00, ...page]);
  }

  async readPage(byteAddress: number, length: number): Promise<Uint8Array> {
    await this.#loadAddress(byteAddress, length);
    const answer = await this.#command([CMD.READ_FLASH_ISP, length >> 8, length & 0xff, 0x20]);
    return answer.slice(2, 2 + length);
  }

  /** Sets the address, unless the bootloader's own count is there already: one round trip a page, not two. */
  async #loadAddress(byteAddress: number, length: number): Promise<void> {
    const here = this.#next;
    this.#next = byteAddress + length;
    if (here === byteAddress) return;
    const word = byteAddress >>> 1;
    // Bit 31: the address is past 64 K words' reach of the old commands (avrdude sets it for big chips).
    const top = (word >>> 24) | (byteAddress >= 0x20000 ? 0x80 : 0);
    await this.#command([CMD.LOAD_ADDRESS, top, (word >> 16) & 0xff, (word >> 8) & 0xff, word & 0xff]);
  }

  async #command(body: number[], timeoutMs = this.timeoutMs): Promise<Uint8Array> {
    this.#next = body[0] === CMD.PROGRAM_FLASH_ISP || body[0] === CMD.READ_FLASH_ISP || body[0] === CMD.LOAD_ADDRESS ? this.#next : -1;
    const sequence = (this.#sequence = (this.#sequence + 1) & 0xff);
    await this.link.write(frame(sequence, body));
    // Stray bytes before the answer (noise, the rest of an answer given up on) are skipped to its start.
    const until = Date.now() + timeoutMs;
    const left = () => {
      if (Date.now() >= until) throw new LinkTimeout(`no answer within ${timeoutMs} ms`);
      return until - Date.now();
    };
    while ((await this.link.read(1, left()))[0] !== MESSAGE_START);
    const head = [MESSAGE_START, ...(await this.link.read(4, left()))];
    if (head[4] !== TOKEN) throw new ProtocolError('the answer does not start as an STK500 v2 message');
    if (head[1] !== sequence) throw new ProtocolError(`the answer is to message ${head[1]}, not ${sequence}`);
    const size = (head[2] << 8) | head[3];
    const rest = await this.link.read(size + 1, timeoutMs);
    const all = [...head, ...rest];
    if (all.reduce((x, b) => x ^ b, 0) !== 0) throw new ProtocolError('the answer fails its checksum');
    const answer = rest.subarray(0, size);
    if (answer[0] !== body[0] || answer[1] !== STATUS_CMD_OK) throw new ProtocolError(`command 0x${body[0].toString(16)} failed (status 0x${answer[1]?.toString(16)})`);
    return answer;
  }
}
