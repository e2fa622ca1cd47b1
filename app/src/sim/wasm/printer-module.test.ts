// The firmware's own C++ as WebAssembly answers as the Mega does: both ports start, each with its
// own receive window, it homes, and a feed rate set once holds for the moves after it (Marlin).
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { beforeAll, describe, expect, it } from 'vitest';
import { type HostPort, PrinterModule } from './printer-module';

let bytes: Uint8Array<ArrayBuffer>;

beforeAll(() => {
  // From the firmware's sources, rebuilt where they changed (npm test installs clang's wasm32 parts).
  execFileSync('bash', ['scripts/build-wasm.sh'], { stdio: 'pipe' });
  bytes = new Uint8Array(readFileSync('build/wasm/printer.wasm'));
}, 600_000);

async function powerUp(): Promise<PrinterModule> {
  const m = await PrinterModule.load(bytes);
  m.start();
  m.run(100_000);
  return m;
}

/** Sends a plain line and runs until its ok; everything the port read meanwhile. */
function ask(m: PrinterModule, line: string, port: HostPort = 0, maxUs = 30_000_000): string[] {
  m.receive(port, line + '\n');
  const got: string[] = [];
  for (let t = 0; t < maxUs; t += 1000) {
    m.run(1000);
    got.push(...m.sent(port));
    if (got.some((l) => l.startsWith('ok'))) return got;
  }
  throw new Error(`no ok for ${line}: ${got.join(' | ')}`);
}

describe('the firmware as WebAssembly', { timeout: 60_000 }, () => {
  it('starts on both ports and gives each its own receive window', async () => {
    const m = await powerUp();
    expect(m.sent(0)).toContain('start');
    expect(m.sent(1)).toContain('start');
    const usb = ask(m, 'M115');
    expect(usb[0]).toMatch(/^FIRMWARE_NAME:UVExposure [\d.]+ \(Mega\)/);
    expect(usb).toContain('Cap:RX_WINDOW:3');
    expect(ask(m, 'M115', 1)).toContain('Cap:RX_WINDOW:2');
  });

  it('homes, and keeps a feed rate set once for the moves after it', async () => {
    const m = await powerUp();
    expect(ask(m, 'G28').at(-1)).toMatch(/^ok/);
    ask(m, 'G1 X10 F600');
    ask(m, 'M400');
    const from = m.position(0);
    m.receive(0, 'G1 X20\n');  // no F: still 10 mm/s, not the 100 mm/s travel speed
    m.run(300_000);
    const partway = m.position(0);
    expect(m.sent(0).some((l) => l.startsWith('ok'))).toBe(true);  // queued at once: its ok came
    ask(m, 'M400');
    const to = m.position(0);
    expect(to).toBeGreaterThan(from);
    // 10 mm at 10 mm/s is 1 s: after 0.3 s the head is at most a third of the way.
    expect((partway - from) / (to - from)).toBeLessThan(0.34);
    expect((partway - from) / (to - from)).toBeGreaterThan(0.1);
  });

  it('refuses a time that is not a whole 32-bit count of microseconds', async () => {
    const m = await powerUp();
    expect(() => m.run(-1)).toThrow(RangeError);
    expect(() => m.run(2 ** 32)).toThrow(RangeError);
  });
});
