// The bytes a bootloader exchanges with the host: a write, and a read of exactly n bytes that waits at
// most a time-out. Over Web Serial (SerialLink) in the app; over a fake bootloader in the tests.

/** The bootloader said nothing (or not enough) in time. */
export class LinkTimeout extends Error {}
/** The port went away: the cable was pulled, or the board lost power. */
export class LinkLost extends Error {}

export interface ByteLink {
  write(bytes: Uint8Array): Promise<void>;
  /** Exactly n bytes, or LinkTimeout after `timeoutMs` without them, or LinkLost. */
  read(n: number, timeoutMs: number): Promise<Uint8Array>;
  /** Drops what has arrived and not been read (a bootloader's answers to a resync). */
  discard(): void;
  /** Resets the board so its bootloader listens again (DTR), where the link can. */
  reset?(): Promise<void>;
}

/** Bytes arriving in chunks, handed out n at a time: the part of a link that tests share. */
export class ByteQueue {
  #buffered: number[] = [];
  #waiter: { n: number; resolve(b: Uint8Array): void; reject(e: Error): void; timer: ReturnType<typeof setTimeout> } | null = null;
  #lost: Error | null = null;

  push(chunk: Uint8Array): void {
    for (const b of chunk) this.#buffered.push(b);
    this.#settle();
  }

  lose(error: Error): void {
    this.#lost = error;
    if (this.#waiter) {
      clearTimeout(this.#waiter.timer);
      this.#waiter.reject(error);
      this.#waiter = null;
    }
  }

  read(n: number, timeoutMs: number): Promise<Uint8Array> {
    if (this.#waiter) return Promise.reject(new Error('one read at a time'));
    if (this.#lost && this.#buffered.length < n) return Promise.reject(this.#lost);
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.#waiter = null;
        reject(new LinkTimeout(`no answer within ${timeoutMs} ms`));
      }, timeoutMs);
      this.#waiter = { n, resolve, reject, timer };
      this.#settle();
    });
  }

  discard(): void {
    this.#buffered = [];
  }

  #settle(): void {
    const w = this.#waiter;
    if (!w || this.#buffered.length < w.n) return;
    clearTimeout(w.timer);
    this.#waiter = null;
    w.resolve(Uint8Array.from(this.#buffered.splice(0, w.n)));
  }
}
