// Faults on the simulated serial link: corrupted and dropped bytes, stalls and a disconnect, from a seeded RNG.

export interface LinkFaults {
  /** Chance per byte, in %, that one bit flips (both directions). */
  corruptPercent?: number;
  /** Chance per byte, in %, that it is lost (both directions). */
  dropPercent?: number;
  /** Every `stallEveryMs`, the printer stops reading for `stallMs`. */
  stallEveryMs?: number;
  stallMs?: number;
  /** The link drops after this long, ms of virtual time. */
  disconnectAfterMs?: number;
  seed?: number;
}

export class FaultyLink {
  #x: number;
  constructor(private readonly f: LinkFaults) {
    this.#x = (f.seed ?? 12345) >>> 0 || 1;
  }

  get active(): boolean {
    return !!(this.f.corruptPercent || this.f.dropPercent);
  }

  #rand(): number {
    let x = this.#x;
    x ^= x << 13;
    x >>>= 0;
    x ^= x >>> 17;
    x ^= x << 5;
    x >>>= 0;
    this.#x = x;
    return x / 4294967296;
  }

  /** Bytes after the link's damage. */
  pass(bytes: string): string {
    if (!this.active) return bytes;
    let out = '';
    for (let i = 0; i < bytes.length; i++) {
      if (this.f.dropPercent && this.#rand() * 100 < this.f.dropPercent) continue;
      let c = bytes.charCodeAt(i);
      if (this.f.corruptPercent && this.#rand() * 100 < this.f.corruptPercent) c ^= 1 << Math.floor(this.#rand() * 8);
      out += String.fromCharCode(c);
    }
    return out;
  }
}
