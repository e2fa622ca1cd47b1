// The Mega's two M29 refusals of a scan job, made by its own C++ (the simulated printer is the
// firmware as WebAssembly) and met through the app's device layer: the TypeScript printer that
// once stood in for it ran both jobs (issue 27).
import { describe, expect, it } from 'vitest';
import { CommandError } from '../../device/command-error';
import { DialectLink } from '../../device/dialect-link';
import type { PrintJob } from '../../protocol/job-types';
import { SimWire } from '../wire';

/** Runs the machine until `p` settles (at most `maxUs` of its time); its outcome. */
async function settle<T>(wire: SimWire, p: Promise<T>, maxUs = 120_000_000): Promise<T> {
  let done = false;
  p.then(() => (done = true), () => (done = true));
  for (let t = 0; !done && t < maxUs; t += 5000) {
    wire.printer.advance(5);
    await new Promise((resolve) => setImmediate(resolve));  // every promise the bytes settled runs on
  }
  return p;
}

async function connected(): Promise<{ wire: SimWire; link: DialectLink }> {
  const wire = new SimWire();
  const link = new DialectLink(wire.host, wire.clientOptions);
  await settle(wire, link.open(() => {}, () => {}));
  return { wire, link };
}

function scanJob(cols: number, rows: number, fullUs: number, cell: (x: number, y: number) => number, pitchUm = 100): PrintJob {
  return {
    name: 'scan',
    grid: { cols, rows },
    pitchUm: { x: pitchUm, y: pitchUm },
    originUm: { x: 5000, y: 4000 },
    dose: { map: 'linear', fullUs },
    leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'scan' },
    gridData: Array.from({ length: rows }, (_, y) => Array.from({ length: cols }, (_, x) => cell(x, y))),
  };
}

/** The job's upload, and the error the Mega answered it with. */
async function refusal(job: PrintJob): Promise<CommandError> {
  const { wire, link } = await connected();
  const e = await settle(wire, link.startJob(job, () => {}).then(() => null, (err: unknown) => err));
  expect(e).toBeInstanceOf(CommandError);
  return e as CommandError;
}

describe('the Mega at M29, before any light (the firmware as WebAssembly)', { timeout: 60_000 }, () => {
  it('a scan job with a pass of 2100 s or more: its stroke counts 0.5 µs ticks in 32 bits', async () => {
    // 5 mm cells at 10 s each, every other one lit: a pass of 240 windows takes 2400 s.
    const e = await refusal(scanJob(240, 4, 10_000_000, (x) => (x % 2 ? 255 : 0), 5000));
    expect(e.code).toBe(29);
  });

  it("takes a photo whose programs would outrun the 115200-baud printhead link, its passes slowed to fit (planner.md)", async () => {
    // Every cell another gray: each LED switches twice a 2 ms window. The planner widens the
    // windows until each pass's program fits the link, so the Mega's M29 guard finds nothing to refuse.
    const { wire, link } = await connected();
    await settle(wire, link.command('G28'));
    await settle(wire, link.startJob(scanJob(200, 8, 2000, (x, y) => 1 + ((x * 97 + y * 31) % 253)), () => {}));
  });

  it('takes a scan job that fits both', async () => {
    const { wire, link } = await connected();
    await settle(wire, link.command('G28'));
    await settle(wire, link.startJob(scanJob(40, 8, 2000, (x, y) => ((x + y) % 5 ? 0 : 255)), () => {}));
  });
});
