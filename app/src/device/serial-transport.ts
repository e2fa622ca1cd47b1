// Transport over Web Serial (Chromium's navigator.serial): USB straight to the Mega.

import { bytesToLatin1, latin1ToBytes } from '../protocol/bytes';
import { NoSerialApi, PickerDismissed } from './serial-support';
import type { Transport } from './transport';

export { PickerDismissed };

export const BAUD_RATE = 115200;
/** The port's receive buffer; a job upload's replies and reports must never overflow it. */
export const READ_BUFFER = 4096;


/** What the transport needs of navigator.serial (and of web-serial-polyfill's stand-in). */
export interface SerialApi {
  requestPort(): Promise<SerialPort>;
}

/** Chromium's Web Serial, or web-serial-polyfill over WebUSB where it is missing (Android Chrome). */
export async function serialApi(): Promise<SerialApi> {
  if ('serial' in navigator) return navigator.serial;
  if ('usb' in navigator) {
    const { serial } = await import('web-serial-polyfill'); // only loaded where it is needed
    return serial as unknown as SerialApi;
  }
  throw new NoSerialApi();
}

export class SerialTransport implements Transport {
  readonly kind = 'serial' as const;
  #port: SerialPort | null = null;
  #reader: ReadableStreamDefaultReader<Uint8Array> | null = null;
  // One writer for the port's life: the windowed sender writes without waiting, and the stream queues
  // the writes in order. A writer per send would find the stream locked by the previous one.
  #writer: WritableStreamDefaultWriter<Uint8Array> | null = null;
  #closing = false;
  #loop: Promise<void> | null = null;

  constructor(private readonly api: () => Promise<SerialApi> = serialApi) {}

  async open(onBytes: (bytes: string) => void, onClosed: (error?: Error) => void): Promise<void> {
    let port: SerialPort;
    try {
      port = await (await this.api()).requestPort();
    } catch (e) {
      if ((e as DOMException).name === 'NotFoundError') throw new PickerDismissed('no port chosen');
      throw e;
    }
    await port.open({ baudRate: BAUD_RATE, bufferSize: READ_BUFFER });
    this.#port = port;
    this.#writer = port.writable?.getWriter() ?? null;
    this.#closing = false;
    this.#loop = this.#readLoop(port, onBytes, onClosed);
  }

  async #readLoop(port: SerialPort, onBytes: (bytes: string) => void, onClosed: (error?: Error) => void) {
    let lost: Error | undefined;
    // A framing, parity, break or overrun error ends one reader; the port stays readable, so take another.
    while (port.readable && !this.#closing) {
      this.#reader = port.readable.getReader();
      try {
        for (;;) {
          const { value, done } = await this.#reader.read();
          if (done) break;
          if (value) onBytes(bytesToLatin1(value));
        }
      } catch (e) {
        if (!this.#closing && (e as DOMException).name === 'NetworkError') lost = e as Error; // device gone
      } finally {
        this.#reader.releaseLock();
        this.#reader = null;
      }
      if (lost) break;
    }
    if (!this.#closing) onClosed(lost ?? new Error('serial port closed'));
  }

  async send(bytes: string): Promise<void> {
    if (!this.#writer) throw new Error('serial port is not open');
    await this.#writer.write(latin1ToBytes(bytes));
  }

  /** Releases both streams before closing, so the port is left with no locked stream. */
  async close(): Promise<void> {
    this.#closing = true;
    await this.#reader?.cancel().catch(() => {});
    await this.#loop; // the loop releases the reader's lock; port.close() refuses locked streams
    this.#loop = null;
    if (this.#writer) {
      await this.#writer.close().catch(() => {});
      this.#writer.releaseLock();
      this.#writer = null;
    }
    await this.#port?.close().catch(() => {});
    this.#port = null;
  }
}
