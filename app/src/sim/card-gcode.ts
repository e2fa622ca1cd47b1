// G-code files on the simulated Mega's card (protocol/mega.md "G-code files on the card"): which names are
// G-code, an upload that stores lines, and a file that runs line by line between the host's lines.

/** G-code files end in .gco, .gcode or .g; every other name on the card is an exposure job. */
export function isGcodeName(name: string): boolean {
  return /.\.(gco|gcode|g)$/i.test(name);
}

/** An M28 of a G-code name: the lines of its port, stored, not run, until M29 shows the file. */
export interface GcodeUpload {
  file: string;
  lines: string[];
}

/** A selected G-code file: where it reads, and whether it runs (M24) or waits (M23, M25). */
export class CardPrint {
  /** The byte after the last line read, as Marlin's `SD printing byte` counts. */
  pos = 0;
  running = false;

  constructor(readonly file: string, readonly text: string) {}

  get size(): number {
    return this.text.length;
  }

  /** The next line to run, without its comment; null while paused; 'end' once every line has been read. */
  next(): string | null | 'end' {
    if (!this.running) return null;
    while (this.pos < this.size) {
      const nl = this.text.indexOf('\n', this.pos);
      const body = this.text.slice(this.pos, nl < 0 ? this.size : nl).replace(/;.*$/, '').trim();
      this.pos = nl < 0 ? this.size : nl + 1;
      if (body) return body;
    }
    return 'end';
  }

  /** M26: a position inside a line moves on to the next line's start, so no line runs from its middle. */
  seek(pos: number): void {
    let p = Math.max(0, Math.min(pos, this.size));
    if (p > 0 && this.text[p - 1] !== '\n') {
      const nl = this.text.indexOf('\n', p);
      p = nl < 0 ? this.size : nl + 1;
    }
    this.pos = p;
  }

  statusLine(): string {
    return `SD printing byte ${this.pos}/${this.size}`;
  }
}
