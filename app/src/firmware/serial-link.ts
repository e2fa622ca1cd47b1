// A ByteLink over a Web Serial port, at the bootloader's baud, with the DTR pulse that resets an Arduino.

import { ByteQueue, LinkLost, type ByteLink } from './byte-link';

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

/** From the reset to the first byte: past the 65 ms the chip spends in reset after the pulse. */
export const RESET_SETTLE_MS = 100;

export class SerialLink implements ByteLink {
  #queue = new ByteQueue();
  #reader: ReadableStreamDefaultReader<Uint8Array> | null = null;
  #writer: WritableStreamDefaultWriter<Uint8Array>;
  #loop: Promise<void>;

  private constructor(private readonly port: SerialPort) {
    this.#writer = port.writable!.getWriter();
    this.#loop = this.#pump();
  }

  static async open(port: SerialPort, baudRate: number): Promise<SerialLink> {
    await port.open({ baudRate, bufferSize: 4096 });
    return new SerialLink(port);
  }

  async #pump(): Promise<void> {
    const reader = (this.#reader = this.port.readable!.getReader());
    try {
      for (;;) {
        const { value, done } = await reader.read();
        if (done) break;
        if (value) this.#queue.push(value);
      }
      this.#queue.lose(new LinkLost('the port was closed'));
    } catch (e) {
      this.#queue.lose(new LinkLost((e as Error).message));
    } finally {
      reader.releaseLock();
    }
  }

  /**
   * DTR (and RTS) low then high: the rising DTR reaches RESET through the board's 100 nF capacitor as a
   * pulse. The chip then stays in reset for its start-up time-out (14 CK + 65 ms with Arduino's low fuse
   * 0xFF) and loses whatever arrives meanwhile: the first byte goes 100 ms after, as avrdude's does, and
   * what came before (a running firmware's last words) is dropped.
   */
  async reset(): Promise<void> {
    await this.port.setSignals({ dataTerminalReady: false, requestToSend: false });
    await sleep(250);
    await this.port.setSignals({ dataTerminalReady: true, requestToSend: true });
    await sleep(RESET_SETTLE_MS);
    this.#queue.discard();
  }

  async write(bytes: Uint8Array): Promise<void> {
    try {
      await this.#writer.write(bytes);
    } catch (e) {
      throw new LinkLost((e as Error).message);
    }
  }

  read(n: number, timeoutMs: number): Promise<Uint8Array> {
    return this.#queue.read(n, timeoutMs);
  }

  discard(): void {
    this.#queue.discard();
  }

  /** Reads one text line (without its end), or null when none ends within `timeoutMs`. */
  async readLine(timeoutMs: number): Promise<string | null> {
    const until = Date.now() + timeoutMs;
    let line = '';
    while (Date.now() < until) {
      let b: Uint8Array;
      try {
        b = await this.#queue.read(1, until - Date.now());
      } catch (e) {
        if (e instanceof LinkLost) throw e;
        return null;
      }
      if (b[0] === 0x0a) return line.replace(/\r$/, '');
      line += String.fromCharCode(b[0]);
    }
    return null;
  }

  /** Lets the port go, whatever state it is in (a pulled cable leaves it errored). */
  async close(): Promise<void> {
    await this.#reader?.cancel().catch(() => {});
    await this.#loop;
    await this.#writer.close().catch(() => {});
    this.#writer.releaseLock();
    await this.port.close().catch(() => {});
  }
}
