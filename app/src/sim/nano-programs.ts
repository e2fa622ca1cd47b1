// The simulated printhead's two scan-program buffers (protocol/nano.md "Scan programs"): the
// firmware's ScanStore (firmware/nano/src/scan_store.*) in TypeScript, for the Nano model.

import { checkEvents, parseAppend, parseSeal, PROGRAM_EVENTS, SEAL_CONTINUATION, SEAL_MORE } from '../protocol/scan-program';

/** The K reply's codes. */
export const SEAL = { ARMED: 0, NO_LOAD: 1, MISMATCH: 2, CAPPED: 3, ENDS_LIT: 4, TOO_MANY: 5, NO_BUFFER: 6, BAD_START: 7 } as const;
/** The Q reply's pass states. */
export const PASS = { NONE: 0, RUNNING: 1, WHOLE: 2, CUT_BY_RESET: 3, CUT_BY_FAULT: 4, UNDERRUN: 5, REFUSED: 6, CUT_BY_SILENCE: 7 } as const;

type State = 'free' | 'loading' | 'armed' | 'running';
interface Buffer {
  state: State;
  events: [number, number][];
  flags: number;
  order: number;
}

export type Step = { d: number; m: number } | 'end' | 'underrun';

export class NanoPrograms {
  readonly #buf: Buffer[] = [0, 1].map(() => ({ state: 'free' as State, events: [], flags: 0, order: 0 }));
  #loading: number | null = null;
  #nextSeq = 0;
  #loadError: number = SEAL.NO_LOAD;
  #newest: number | null = null;
  #chainMask = 0;
  #chainTail = [0, 0, 0, 0];
  #order = 0;
  #run: number | null = null;
  #pos = 0;
  pass: number = PASS.NONE;

  constructor(private readonly capUs: number) {}

  /** An A line (without terminator); false when malformed (the Nano latches MALFORMED). */
  append(line: string): boolean {
    const a = parseAppend(line);
    if (!a) {
      this.#spoil(SEAL.NO_LOAD);
      return false;
    }
    if (a.seq === 0) {
      if (this.#loading !== null) this.#buf[this.#loading].state = 'free';
      this.#loading = null;
      this.#buf.forEach((b, i) => { if (b.state === 'free') this.#loading = i; });
      if (this.#loading === null) {
        this.#loadError = SEAL.NO_BUFFER;
      } else {
        Object.assign(this.#buf[this.#loading], { state: 'loading', events: [] });
        this.#nextSeq = 0;
      }
    }
    if (this.#loading === null) return true; // a spoiled load drops its lines
    if (a.seq !== this.#nextSeq) {
      this.#spoil(SEAL.NO_LOAD);
      return true;
    }
    this.#nextSeq++;
    const b = this.#buf[this.#loading];
    if (b.events.length + a.events.length > PROGRAM_EVENTS) {
      this.#spoil(SEAL.TOO_MANY);
      return true;
    }
    b.events.push(...a.events);
    return true;
  }

  /** A K line: the reply's code, or null when the line is malformed. */
  seal(line: string): number | null {
    const s = parseSeal(line);
    if (!s) return null;
    const i = this.#loading;
    if (i === null) {
      const why = this.#loadError;
      this.#loadError = SEAL.NO_LOAD;
      return why;
    }
    this.#loading = null;
    this.#loadError = SEAL.NO_LOAD;
    const b = this.#buf[i];
    const continuation = (s.flags & SEAL_CONTINUATION) !== 0;
    const more = (s.flags & SEAL_MORE) !== 0;
    const after = this.#live(this.#newest) && (this.#buf[this.#newest!].flags & SEAL_MORE) !== 0;
    let mask = continuation ? this.#chainMask : 0;
    const tail = continuation ? [...this.#chainTail] : [0, 0, 0, 0];
    let verdict: number = SEAL.ARMED;
    if (b.events.length !== s.events || checkEvents(b.events) !== s.check) verdict = SEAL.MISMATCH;
    else if (continuation !== after || (continuation && b.events[0][0] === 0)) verdict = SEAL.BAD_START;
    else {
      for (const [d, next] of b.events) {
        for (let k = 0; k < 4; k++) {
          if (!((mask >> k) & 1)) continue;
          const t = tail[k] + d;
          if (t > this.capUs) verdict = SEAL.CAPPED;
          tail[k] = (next >> k) & 1 ? t : 0;
        }
        mask = next;
        if (verdict !== SEAL.ARMED) break;
      }
      if (verdict === SEAL.ARMED && !more && mask) verdict = SEAL.ENDS_LIT;
    }
    if (verdict !== SEAL.ARMED) {
      b.state = 'free';
      return verdict;
    }
    Object.assign(b, { state: 'armed', flags: s.flags, order: this.#order++ });
    this.#chainMask = mask;
    this.#chainTail = tail;
    this.#newest = i;
    return verdict;
  }

  get free(): number {
    return this.#buf.filter((b) => b.state === 'free' || b.state === 'loading').length;
  }

  get armed(): number {
    return this.#buf.filter((b) => b.state === 'armed').length;
  }

  get running(): boolean {
    return this.#run !== null;
  }

  /** The oldest armed program starts a chain, and nothing runs. */
  startable(): boolean {
    const o = this.#oldest();
    return this.#run === null && o !== null && (this.#buf[o].flags & SEAL_CONTINUATION) === 0;
  }

  start(): void {
    const o = this.#oldest();
    if (o === null) return;
    this.#buf[o].state = 'running';
    this.#run = o;
    this.#pos = 0;
    this.pass = PASS.RUNNING;
  }

  /** The running chain's next event, d µs after the one before (or time 0). */
  next(): Step {
    const r = this.#run;
    if (r === null) return 'end';
    const b = this.#buf[r];
    if (this.#pos === b.events.length) {
      const o = this.#buf[r ^ 1];
      const more = (b.flags & SEAL_MORE) !== 0;
      b.state = 'free';
      if (!more || o.state !== 'armed' || !(o.flags & SEAL_CONTINUATION)) {
        this.#run = null;
        this.pass = more ? PASS.UNDERRUN : PASS.WHOLE;
        return more ? 'underrun' : 'end';
      }
      o.state = 'running';
      this.#run = r ^ 1;
      this.#pos = 0;
      return this.next();
    }
    const [d, m] = b.events[this.#pos++];
    return { d, m };
  }

  /** Every program dropped; the pass becomes `why` if one ran. */
  discard(why: number): void {
    if (this.#run !== null) this.pass = why;
    this.#run = this.#loading = this.#newest = null;
    for (const b of this.#buf) b.state = 'free';
  }

  #live(i: number | null): boolean {
    return i !== null && (this.#buf[i].state === 'armed' || this.#buf[i].state === 'running');
  }

  #oldest(): number | null {
    let o: number | null = null;
    this.#buf.forEach((b, i) => {
      if (b.state === 'armed' && (o === null || b.order < this.#buf[o].order)) o = i;
    });
    return o;
  }

  #spoil(why: number): void {
    if (this.#loading !== null) this.#buf[this.#loading].state = 'free';
    this.#loading = null;
    this.#loadError = why;
  }
}
