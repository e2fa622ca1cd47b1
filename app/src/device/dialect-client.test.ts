import { describe, expect, it } from 'vitest';
import { GEOMETRIES, planCase, randomJob } from '../planner/test-jobs';
import { encodeJob } from '../protocol/job-encode';
import { SimWire } from '../sim/wire';
import { CommandError } from './command-error';
import { DialectClient } from './dialect-client';
import type { Transport } from './transport';
import { SimPrinter } from '../sim/sim-printer';
import { DialectLink } from './dialect-link';
import { formatOk } from '../protocol/reply-format';
import type { LinkFaults } from '../sim/link-faults';
import { CONFIG_DEFAULTS, motionOf } from '../machine/config';

function rig(link: LinkFaults = {}, noSd = false) {
  const wire = new SimWire({ link, noSd });
  const dl = new DialectLink(wire.host, wire.clientOptions);
  const lines: string[] = [];
  let closed: Error | undefined;
  const opened = dl.open((_r, line) => lines.push(line), (e) => (closed = e ?? new Error('closed')));
  return { wire, dl, lines, opened, closed: () => closed };
}

/** Runs virtual time until the promise settles. */
async function settle<T>(wire: SimWire, p: Promise<T>, maxMs = 180_000): Promise<T> {
  let done = false;
  p.then(() => (done = true), () => (done = true));
  for (let t = 0; t < maxMs && !done; t += 5) {
    wire.runUntil(() => done, 5);
    for (let i = 0; i < 10; i++) await Promise.resolve(); // let the client's awaits run between steps
  }
  return p;
}

function job(seed: number) {
  const j = randomJob(seed, GEOMETRIES.adjacent, 'serpentine', [60, 24], 0.5);
  j.dose = { map: 'linear', fullUs: 3000 };
  return j;
}

describe('dialect client over a simulated 115200-baud wire', () => {
  it('learns the window from M115 and matches replies to commands', async () => {
    const r = rig();
    await settle(r.wire, r.opened);
    const temps = await settle(r.wire, r.dl.command('M105'));
    expect(temps[0].kind).toBe('temps');
    await expect(settle(r.wire, r.dl.command('G0 X1'))).rejects.toEqual(new CommandError(14, 'axis not homed: X'));
    await settle(r.wire, r.dl.command('G28'));
    const [pos] = await settle(r.wire, r.dl.command('M114'));
    if (pos.kind !== 'position') console.log(r.lines.slice(-30));
    expect(pos).toMatchObject({ kind: 'position', um: [0, 0, 0] });
    expect(r.lines).toContain('Cap:RX_WINDOW:3');
    expect(r.dl.linkBaud).toBe(250000); // Cap:LINK_BAUD: its Nano takes the raised printhead link speed
  });

  it('uploads a job bit-exact through 1 % byte corruption with drops', async () => {
    const r = rig({ corruptPercent: 1, dropPercent: 0.3, seed: 99 });
    await settle(r.wire, r.opened);
    await settle(r.wire, r.dl.command('G28'));
    const j = job(21);
    const progress: number[] = [];
    await settle(r.wire, r.dl.startJob(j, (p) => progress.push(p.bytesVerified)));
    const stored = r.wire.printer.module.card().map(([, text]) => text);
    expect(r.dl.jobFormat).toBe(2); // the printer says Cap:JOB_FORMAT:2: run-length rows where shorter
    expect(stored).toContain(encodeJob(j, 2));
    expect(r.dl.health.resends + r.dl.health.timeouts).toBeGreaterThan(0);
    expect(r.dl.health.bytesRetransmitted).toBeGreaterThan(0);
    expect(progress.at(-1)).toBe(encodeJob(j, 2).length);
    expect(r.wire.printer.module.cardJob()).not.toBeNull(); // running
  });

  it('rejects what is pending when the link drops', async () => {
    const r = rig({ disconnectAfterMs: 1500 });
    await settle(r.wire, r.opened);
    const pending = r.dl.command('G4 S10');
    await expect(settle(r.wire, pending)).rejects.toThrow('device lost');
    expect(r.closed()?.message).toBe('device lost');
  });

  it('keeps the Mega busy through its window: a 20 kB upload needs no resend on a clean wire', async () => {
    const r = rig();
    await settle(r.wire, r.opened);
    await settle(r.wire, r.dl.command('G28'));
    const j = job(7);
    r.dl.jobFormat = 1; // hex rows: 20 kB of them, where run-length rows would be a few
    const text = encodeJob(j, 1);
    const start = r.wire.printer.clock.now;
    await settle(r.wire, r.dl.startJob({ ...j, gridData: j.gridData }, () => {}));
    const seconds = (r.wire.printer.clock.now - start) / 1e6;
    expect(r.dl.health.resends).toBe(0);
    expect(text.length / seconds).toBeGreaterThan(0.8 * 11520 * (text.length / r.wire.carried.toPrinter));
    // The rate the next question uses: measured on this upload, in the printer's time, at most the line's.
    expect(r.dl.uploadRate.measured).toBe(true);
    expect(r.dl.uploadRate.bytesPerS).toBeGreaterThan(0.8 * 11520);
    expect(r.dl.uploadRate.bytesPerS).toBeLessThanOrEqual(11520);
  });

  it('streams with M828 on a Mega without SD, held back by its buffer, with no time-out and every stop once', async () => {
    const r = rig({}, true);
    await settle(r.wire, r.opened);
    await settle(r.wire, r.dl.command('G28'));
    const j = randomJob(12, GEOMETRIES.adjacent, 'serpentine', [60, 40], 0.9); // what the Mega's stream window takes (a bigger one is E28)
    j.dose = { map: 'linear', fullUs: 3000 };
    const printer = r.wire.printer;
    const { stops } = planCase('', j, motionOf(CONFIG_DEFAULTS, [0, 0])).plan;
    await settle(r.wire, r.dl.startJob(j, () => {}), 600_000);
    expect(r.lines).toContain('echo:Streaming: exposed as it arrives, no resume');
    expect(r.lines.filter((l) => l.startsWith('busy:')).length).toBeGreaterThan(0); // it was held back
    expect(r.dl.health.timeouts).toBe(0);
    expect(r.dl.health.resends).toBe(0);
    r.wire.runUntil(() => r.lines.some((l) => l.startsWith('JOB:done')), 600_000);
    expect(r.lines.find((l) => l.startsWith('JOB:done'))).toContain(`stop=${stops.length}/${stops.length}`);
    expect(printer.module.fires).toBe(stops.filter((s) => s.slice(2).some((us) => us > 0)).length);
  });
});

/**
 * A Mega's USB port, as a host opening it meets it: the port's DTR resets the Mega, its bootloader
 * waits `bootloaderMs` (bytes sent meanwhile are lost), then the firmware starts and says `start`.
 * With `bootloaderMs` null the port does not reset the board: its firmware runs on, silent.
 */
class MegaPort implements Transport {
  readonly kind = 'serial' as const;
  readonly printer: SimPrinter;
  lost = 0;
  #onBytes: (b: string) => void = () => {};
  #bootingUntil = 0;

  /** `latencyUs`: one way, what lies between (a USB frame; a test harness's page round trip). */
  constructor(private readonly bootloaderMs: number | null, private readonly latencyUs = 1000) {
    this.printer = new SimPrinter((b) => {
      if (this.printer.clock.now >= this.#bootingUntil) this.printer.clock.after(this.latencyUs, () => this.#onBytes(b));
    });
  }

  async open(onBytes: (b: string) => void): Promise<void> {
    this.#onBytes = onBytes;
    if (this.bootloaderMs === null) return;
    this.#bootingUntil = this.printer.clock.now + this.bootloaderMs * 1000;
    this.printer.clock.after(this.bootloaderMs * 1000, () => this.printer.boot());
  }

  async send(bytes: string): Promise<void> {
    if (this.printer.clock.now < this.#bootingUntil) this.lost += bytes.length;
    else this.printer.clock.after(this.latencyUs, () => this.printer.receive(bytes));
  }

  async close(): Promise<void> {}

  readonly clientOptions = {
    now: () => this.printer.clock.now / 1000,
    setTimer: (fn: () => void, ms: number) => this.printer.clock.after(ms * 1000, fn),
    clearTimer: (t: unknown) => this.printer.clock.cancel(t as object),
  };

  /** Runs virtual time until the promise settles; resolves with it and the virtual ms it took. */
  async settle<T>(p: Promise<T>, maxMs = 30_000): Promise<{ value: T; ms: number }> {
    const clock = this.printer.clock, from = clock.now;
    let done = false;
    p.then(() => (done = true), () => (done = true));
    while (!done && clock.now - from < maxMs * 1000) {
      this.printer.advanceTo(Math.max(clock.now + 100, Math.min(clock.next, clock.now + 5000)));
      for (let i = 0; i < 10; i++) await Promise.resolve();
    }
    return { value: await p, ms: (clock.now - from) / 1000 };
  }
}

describe('the first exchange of a link', () => {
  it("waits for the Mega's `start` after the port resets it: nothing is lost to its bootloader, nothing times out", async () => {
    const port = new MegaPort(1000);
    const client = new DialectClient(port, () => {}, port.clientOptions);
    const { ms } = await port.settle(client.open(() => {}));
    await port.settle(client.command('M115'));
    expect(port.lost).toBe(0);
    expect(client.health).toMatchObject({ timeouts: 0, resends: 0, bytesRetransmitted: 0 });
    expect(ms).toBeGreaterThan(1000);
    expect(ms).toBeLessThan(1200); // the Mega's own 0.1 s start, the wire: no time-out's wait
  });

  it('a board the port did not reset says nothing: the first line goes after the time-out, and is answered', async () => {
    const port = new MegaPort(null);
    const client = new DialectClient(port, () => {}, { ...port.clientOptions, startTimeoutMs: 2000 });
    const { ms } = await port.settle(client.open(() => {}));
    expect(ms).toBeGreaterThanOrEqual(2000);
    expect(ms).toBeLessThan(2100);
    expect((await port.settle(client.command('M115'))).value.some((r) => r.kind === 'firmware')).toBe(true);
    expect(client.health.timeouts).toBe(0);
  });

  it('a slow first round trip is not a time-out: with none measured yet, the first line waits 1 s', async () => {
    const port = new MegaPort(1000, 150_000); // 0.3 s there and back
    const client = new DialectClient(port, () => {}, port.clientOptions);
    await port.settle(client.open(() => {}));
    await port.settle(client.command('M115'));
    expect(client.health.timeouts).toBe(0);
    expect(client.health.rttMs).toBeGreaterThan(300);
  });

  it('sent at once, as before, the first line was lost to the bootloader and came back as a time-out', async () => {
    // What "1 time-outs, 20 bytes again" on every fresh link was: the same port, no wait for `start`.
    const port = new MegaPort(1000);
    const client = new DialectClient(port, () => {}, { ...port.clientOptions, startTimeoutMs: 0 });
    await port.settle(client.open(() => {}));
    expect(port.lost).toBeGreaterThan(0);
    expect(client.health.timeouts).toBeGreaterThan(0);
  });
});

/** A Mega port whose replies the test writes, on a clock the test moves. */
async function scriptedPort() {
  let feed: (bytes: string) => void = () => {};
  let now = 0;
  const timers: { at: number; fn: () => void }[] = [];
  const sent: string[] = [];
  const port: Transport = {
    kind: 'serial',
    open: async (onBytes) => void (feed = onBytes),
    send: async (bytes) => void sent.push(bytes),
    close: async () => {},
  };
  const client = new DialectClient(port, () => {}, {
    now: () => now,
    setTimer: (fn, ms) => {
      const t = { at: now + ms, fn };
      timers.push(t);
      return t;
    },
    clearTimer: (t) => void timers.splice(timers.indexOf(t as (typeof timers)[number]) >>> 0, 1),
  });
  const tick = () => new Promise((resolve) => setTimeout(resolve, 0));
  const opening = client.open(() => {});
  await tick();
  feed('start\n');
  await tick();
  feed(formatOk(Number(/^N(\d+) M110/.exec(sent[0])?.[1]), 8, 3) + '\n');
  await opening;
  return {
    client,
    sent,
    tick,
    feed: (line: string) => feed(line + '\n'),
    /** The number the client gave the last line it sent with `body`. */
    numberOf: (body: string) => Number(new RegExp(`^N(\\d+) ${body}\\*`).exec(sent.filter((f) => f.includes(` ${body}*`)).at(-1) ?? '')?.[1]),
    advance: (ms: number) => {
      now += ms;
      for (const t of timers.filter((x) => x.at <= now)) {
        timers.splice(timers.indexOf(t), 1);
        t.fn();
      }
    },
  };
}

describe('reply blocks', () => {
  // A busy page reads the port late, so the client times out on a long reply such as M503's
  // listing, resends the running line, and the Mega frees the duplicate's slot with a bare ok
  // between the listing's lines (mega.md §2). Either cut the listing: the app read the settings it
  // lost as their defaults, soft limits back at 50 °C, and Continue open on a head still too hot.
  const otherLines = (replies: { kind: string; text?: string }[]) => replies.flatMap((r) => (r.kind === 'other' ? [r.text] : []));

  it("keep a long reply whole when a resent line's ok, with no N, lands inside it", async () => {
    const m = await scriptedPort();
    const reply = m.client.command('M503');
    await m.tick();
    m.feed('M850 thermal.limit.4 50');
    m.feed(formatOk(undefined, 8, 1)); // the resent M503, still running
    m.feed('M850 thermal.limit.5 20');
    m.feed(formatOk(m.numberOf('M503'), 8, 2));
    expect(otherLines(await reply)).toEqual(['M850 thermal.limit.4 50', 'M850 thermal.limit.5 20']);
    await m.client.close();
  });

  it("give a line sent after a quiet spell the whole time-out, not what an earlier line's timer had left", async () => {
    const m = await scriptedPort();
    const temps = m.client.command('M105');
    await m.tick();
    m.feed(formatOk(m.numberOf('M105'), 8, 3)); // answered at once; the link's first timer (1 s) stays armed
    await temps;
    m.advance(800);
    const reply = m.client.command('M503');
    await m.tick();
    m.advance(200); // that timer fires 200 ms after M503 went, under the 250 ms its wait may take
    await m.tick();
    expect(m.client.health.timeouts).toBe(0);
    expect(m.sent.filter((f) => f.includes(' M503*'))).toHaveLength(1);
    m.feed('M850 thermal.limit.5 20');
    m.feed(formatOk(m.numberOf('M503'), 8, 3));
    expect(otherLines(await reply)).toEqual(['M850 thermal.limit.5 20']);
    await m.client.close();
  });

  it('keep a long reply whole across a time-out in its middle', async () => {
    const m = await scriptedPort();
    const reply = m.client.command('M503');
    await m.tick();
    m.feed('M850 thermal.limit.4 50');
    m.advance(5000); // the time-out: M503 goes again
    await m.tick();
    expect(m.sent.filter((f) => f.includes(' M503*'))).toHaveLength(2);
    expect(m.client.health.timeouts).toBe(1);
    m.feed('M850 thermal.limit.5 20');
    m.feed(formatOk(m.numberOf('M503'), 8, 2));
    m.feed(formatOk(m.numberOf('M503'), 8, 3)); // the duplicate, answered already
    expect(otherLines(await reply)).toEqual(['M850 thermal.limit.4 50', 'M850 thermal.limit.5 20']);
    await m.client.close();
  });
});
