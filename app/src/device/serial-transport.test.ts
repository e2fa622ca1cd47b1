import { describe, expect, it } from 'vitest';
import { PickerDismissed, SerialTransport, type SerialApi } from './serial-transport';

/** A port that behaves like Chromium's: a recoverable error ends one readable and a new one takes its place. */
class FakePort {
  opened: SerialOptions | null = null;
  closed = false;
  written = '';
  #controller: ReadableStreamDefaultController<Uint8Array> | null = null;
  #readable: ReadableStream<Uint8Array> | null = null;
  lost = false;
  writable = new WritableStream<Uint8Array>({ write: (c) => void (this.written += new TextDecoder().decode(c)) });

  get readable(): ReadableStream<Uint8Array> | null {
    if (this.lost || this.closed) return null;
    this.#readable ??= new ReadableStream({ start: (c) => void (this.#controller = c) });
    return this.#readable;
  }
  async open(o: SerialOptions) {
    this.opened = o;
  }
  async close() {
    if (this.#readable?.locked || this.writable.locked) throw new TypeError('The port has locked streams');
    this.closed = true;
  }
  send(text: string) {
    this.#controller!.enqueue(new TextEncoder().encode(text));
  }
  /** A break, framing, parity or overrun error ends this readable; the port makes a new one. */
  fail(name: string) {
    this.#controller!.error(new DOMException(name, name));
    this.#readable = null;
  }
  unplug() {
    this.lost = true;
    this.#controller!.error(new DOMException('The device has been lost.', 'NetworkError'));
  }
}

const tick = () => new Promise((r) => setTimeout(r, 0));

function rig() {
  const port = new FakePort();
  const api: SerialApi = { requestPort: async () => port as unknown as SerialPort };
  const t = new SerialTransport(async () => api);
  let got = '';
  let closed: Error | undefined | null = null;
  return { port, t, got: () => got, closed: () => closed, open: () => t.open((b) => (got += b), (e) => (closed = e ?? new Error('closed'))) };
}

describe('Web Serial transport', () => {
  it('opens at 115200 baud with a read buffer of at least 1 KB', async () => {
    const r = rig();
    await r.open();
    expect(r.port.opened?.baudRate).toBe(115200);
    expect(r.port.opened?.bufferSize).toBeGreaterThanOrEqual(1024);
  });

  it('takes a new reader after break, framing, parity and overrun errors, losing nothing after them', async () => {
    const r = rig();
    await r.open();
    r.port.send('ok 1\n');
    await tick();
    for (const name of ['BreakError', 'FramingError', 'ParityError', 'BufferOverrunError']) {
      r.port.fail(name);
      await tick();
      r.port.send(`after ${name}\n`);
      await tick();
    }
    expect(r.got()).toBe('ok 1\nafter BreakError\nafter FramingError\nafter ParityError\nafter BufferOverrunError\n');
    expect(r.closed()).toBeNull();
  });

  it('reports a lost device once', async () => {
    const r = rig();
    await r.open();
    r.port.unplug();
    await tick();
    expect(r.closed()?.name).toBe('NetworkError');
  });

  it('writes in order without locking out the next write, and closes with no locked stream', async () => {
    const r = rig();
    await r.open();
    await Promise.all(['N1 M105\n', 'N2 M114\n', 'N3 G28\n'].map((l) => r.t.send(l)));
    expect(r.port.written).toBe('N1 M105\nN2 M114\nN3 G28\n');
    await r.t.close();
    expect(r.port.closed).toBe(true);
    expect(r.closed()).toBeNull(); // closing on purpose is not a lost link
  });

  it('treats a dismissed port picker as no choice, not an error', async () => {
    const api: SerialApi = { requestPort: async () => Promise.reject(new DOMException('No port selected by the user.', 'NotFoundError')) };
    await expect(new SerialTransport(async () => api).open(() => {}, () => {})).rejects.toBeInstanceOf(PickerDismissed);
  });
});
