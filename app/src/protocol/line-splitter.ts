// Splits a byte stream into newline-terminated lines with a length limit (both serial links).

export interface SplitLine {
  /** The line without its terminator; at most maxLine characters (truncated when overflow). */
  text: string;
  /** The line was longer than maxLine and was cut. */
  overflow: boolean;
}

/**
 * Feed it chunks split anywhere; it yields each complete line. One '\r' before '\n' is
 * dropped. Bytes of an unterminated tail wait for the next chunk.
 */
export class LineSplitter {
  #buf = '';
  #overflow = false;
  constructor(readonly maxLine: number) {}

  push(chunk: string): SplitLine[] {
    const out: SplitLine[] = [];
    for (let i = 0; i < chunk.length; i++) {
      const ch = chunk[i];
      if (ch === '\n') {
        let text = this.#buf;
        if (text.endsWith('\r')) text = text.slice(0, -1);
        const overflow = this.#overflow || text.length > this.maxLine;
        out.push({ text: overflow ? text.slice(0, this.maxLine) : text, overflow });
        this.#buf = '';
        this.#overflow = false;
      } else if (this.#buf.length <= this.maxLine) {
        this.#buf += ch; // one spare byte so a final '\r' still fits
      } else {
        this.#overflow = true;
      }
    }
    return out;
  }

  /** Bytes waiting for their newline. */
  get pending(): number {
    return this.#buf.length;
  }
}
