// The Mega's line-acceptance state machine: numbering, duplicates, resend and resync (protocol/mega.md §2).

import { parseCommand } from './dialect-command';
import { parseFrame } from './dialect-frame';
import { errorByCode, isLineError } from './errors';
import type { SplitLine } from './line-splitter';
import { formatOk } from './reply-format';

export type Acceptance =
  | { kind: 'none' }
  | { kind: 'reply'; lines: string[] }
  | { kind: 'execute'; body: string; n?: number };

export interface FlowCounters {
  movesFree(): number;
  windowFree(): number;
}

export class LineReceiver {
  last = 0;
  /** The highest line whose reply block has gone out (the executor calls markAnswered). */
  answered = 0;
  resyncing = false;

  constructor(private readonly flow: FlowCounters) {}

  /** The executor finished line `n` and is sending its reply block. */
  markAnswered(n: number | undefined): void {
    if (n !== undefined && n > this.answered) this.answered = n;
  }

  /** The `ok` that ends a reply block for line `n`, or for no line. */
  ok(n?: number): string {
    return formatOk(n, this.flow.movesFree(), this.flow.windowFree());
  }

  accept(line: SplitLine): Acceptance {
    if (!line.overflow && line.text === '') return { kind: 'none' };
    const frame = parseFrame(line);
    if (!frame.ok) {
      const message = errorByCode(frame.error)!.message;
      if (frame.numbered && isLineError(frame.error)) return this.#askResend(frame.error, message);
      return { kind: 'reply', lines: [`Error:E${frame.error} ${message}`, this.ok()] };
    }
    const setLine = this.#m110(frame.body, frame.n);
    if (setLine !== null) {
      this.last = setLine;
      this.answered = setLine;
      this.resyncing = false;
      return { kind: 'reply', lines: [this.ok(setLine >= 0 ? setLine : undefined)] };
    }
    if (frame.n === undefined) {
      return frame.body === '' ? { kind: 'reply', lines: [this.ok()] } : { kind: 'execute', body: frame.body };
    }
    if (frame.n === this.last + 1) {
      this.last = frame.n;
      this.resyncing = false;
      if (frame.body !== '') return { kind: 'execute', body: frame.body, n: frame.n };
      this.markAnswered(frame.n);
      return { kind: 'reply', lines: [this.ok(frame.n)] };
    }
    // A duplicate: confirm a line already answered; for one still waiting or running, free the
    // slot and let its own reply answer it (mega.md §2).
    if (frame.n <= this.last) return { kind: 'reply', lines: [this.ok(frame.n <= this.answered ? frame.n : undefined)] };
    if (this.resyncing) return { kind: 'reply', lines: [this.ok()] };
    return this.#askResend(6, errorByCode(6)!.message);
  }

  #askResend(code: number, message: string): Acceptance {
    this.resyncing = true;
    return {
      kind: 'reply',
      lines: [`Error:E${code} ${message}, Last Line: ${this.last}`, `Resend: ${this.last + 1}`, this.ok()],
    };
  }

  /** M110 [N<n>] sets the line number: to its N parameter, else to the frame's own number. */
  #m110(body: string, n: number | undefined): number | null {
    const parsed = parseCommand(body);
    if (!parsed.ok || parsed.command.word !== 'M110' || !('params' in parsed.command)) return null;
    const p = parsed.command.params.N;
    if (typeof p === 'number' && p >= -1000 && p % 1000 === 0) return p / 1000;
    return n ?? null;
  }
}
