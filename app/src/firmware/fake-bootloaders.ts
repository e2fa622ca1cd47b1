// Test-only: bootloaders in TypeScript behind a ByteLink, answering as Optiboot (STK500 v1) and
// stk500boot.c (STK500 v2) do, down to the v2 bootloader erasing pages in its own order. The e2e specs
// meet the real ones in simavr (e2e/bootloader-rig.ts).

import { ByteQueue, LinkLost, type ByteLink } from './byte-link';
import type { Chip } from './chips';
import { frame } from './stk500v2';

export interface FakeBoard {
  link: ByteLink;
  flash: Uint8Array;
  /** Pulls the cable when this many pages have been written. */
  pullAfterPages?: number;
}

abstract class FakeBootloader implements ByteLink {
  readonly flash: Uint8Array;
  pagesWritten = 0;
  pullAfterPages = Infinity;
  protected input: number[] = [];
  #answers = new ByteQueue();
  #pulled = false;

  constructor(readonly chip: Chip) {
    this.flash = new Uint8Array(chip.flashBytes).fill(0xff);
  }

  async write(bytes: Uint8Array): Promise<void> {
    if (this.#pulled) throw new LinkLost('the device has been lost');
    this.input.push(...bytes);
    this.take();
  }

  read(n: number, timeoutMs: number): Promise<Uint8Array> {
    return this.#answers.read(n, timeoutMs);
  }

  discard(): void {
    this.#answers.discard();
  }

  async reset(): Promise<void> {
    this.input = [];
    this.#answers.discard();
  }

  protected answer(bytes: ArrayLike<number>): void {
    this.#answers.push(Uint8Array.from(bytes));
  }

  protected wrotePage(): void {
    if (++this.pagesWritten >= this.pullAfterPages) {
      this.#pulled = true;
      this.#answers.lose(new LinkLost('the device has been lost'));
    }
  }

  protected abstract take(): void;
}

export class FakeOptiboot extends FakeBootloader {
  #address = 0;

  protected take(): void {
    for (;;) {
      const need = this.#length();
      if (need === 0 || this.input.length < need) return;
      const c = this.input.splice(0, need);
      if (c[c.length - 1] !== 0x20) continue; // no CRC_EOP: a real Optiboot resets (watchdog); here it just drops it
      const ok = (data: ArrayLike<number> = []) => this.answer([0x14, ...Array.from(data), 0x10]);
      switch (c[0]) {
        case 0x75: ok(this.chip.signature); break;
        case 0x55: this.#address = (c[1] | (c[2] << 8)) * 2; ok(); break;
        case 0x64: {
          const n = (c[1] << 8) | c[2];
          this.flash.set(c.slice(4, 4 + n), this.#address);
          ok();
          this.wrotePage();
          break;
        }
        case 0x74: ok(this.flash.subarray(this.#address, this.#address + ((c[1] << 8) | c[2]))); break;
        default: ok();
      }
    }
  }

  /** Bytes in the command at the head of the input, 0 if not known yet. */
  #length(): number {
    const c = this.input;
    if (!c.length) return 0;
    if (c[0] === 0x55) return 4;
    if (c[0] === 0x64) return c.length >= 3 ? 5 + ((c[1] << 8) | c[2]) : 0;
    if (c[0] === 0x74) return 5;
    return 2;
  }
}

export class FakeStk500v2 extends FakeBootloader {
  #address = 0;
  #eraseAddress = 0;

  protected take(): void {
    for (;;) {
      while (this.input.length && this.input[0] !== 0x1b) this.input.shift(); // as stk500boot.c: waits for a message start
      if (this.input.length < 5) return;
      const size = (this.input[2] << 8) | this.input[3];
      if (this.input.length < 6 + size) return;
      const m = this.input.splice(0, 6 + size);
      const body = m.slice(5, 5 + size);
      const reply = (rest: number[]) => this.answer(frame(m[1], [body[0], 0x00, ...rest]));
      switch (body[0]) {
        case 0x01: reply([8, ...Array.from('AVRISP_2', (ch) => ch.charCodeAt(0))]); break;
        case 0x1b: reply([this.chip.signature[body[4]], 0x00]); break;
        case 0x06: this.#address = (((body[1] << 24) | (body[2] << 16) | (body[3] << 8) | body[4]) << 1) >>> 0; reply([]); break;
        case 0x13: {
          const n = (body[1] << 8) | body[2];
          // As stk500boot.c: the page erased is the next of its own count, not the one addressed.
          this.flash.fill(0xff, this.#eraseAddress, this.#eraseAddress + this.chip.pageBytes);
          this.#eraseAddress += this.chip.pageBytes;
          const page = body.slice(10, 10 + n);
          for (let i = 0; i < n; i++) this.flash[this.#address + i] &= page[i]; // flash only clears bits
          this.#address += n;
          reply([]);
          this.wrotePage();
          break;
        }
        case 0x14: {
          const n = (body[1] << 8) | body[2];
          reply([...this.flash.subarray(this.#address, this.#address + n), 0x00]);
          this.#address += n;
          break;
        }
        default: reply([]);
      }
    }
  }
}
