// The firmware's own C++ as WebAssembly answers as the Mega does: both ports start, each with its
// own receive window, it homes, and a feed rate set once holds for the moves after it (Marlin).
// Its card, EEPROM and start count go out and come back in, as a reload keeps them.
import { describe, expect, it } from 'vitest';
import { firmwareModule } from './firmware-module';
import { type HostPort, PrinterModule } from './printer-module';

function powerUp(): PrinterModule {
  const m = new PrinterModule(firmwareModule());
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
  it('starts on both ports and gives each its own receive window', () => {
    const m = powerUp();
    expect(m.sent(0)).toContain('start');
    expect(m.sent(1)).toContain('start');
    const usb = ask(m, 'M115');
    expect(usb[0]).toMatch(/^FIRMWARE_NAME:UVExposure [\d.]+ \(Mega\)/);
    expect(usb).toContain('Cap:RX_WINDOW:3');
    expect(ask(m, 'M115', 1)).toContain('Cap:RX_WINDOW:2');
  });

  it('homes, and keeps a feed rate set once for the moves after it', () => {
    const m = powerUp();
    expect(ask(m, 'G28').at(-1)).toMatch(/^ok/);
    ask(m, 'G1 X10 F600');
    ask(m, 'M400');
    const from = m.position(0);
    m.receive(0, 'G1 X20\n'); // no F: still 10 mm/s, not the 100 mm/s travel speed
    m.run(300_000);
    const partway = m.position(0);
    expect(m.sent(0).some((l) => l.startsWith('ok'))).toBe(true); // queued at once: its ok came
    ask(m, 'M400');
    const to = m.position(0);
    expect(to).toBeGreaterThan(from);
    // 10 mm at 10 mm/s is 1 s: after 0.3 s the head is at most a third of the way.
    expect((partway - from) / (to - from)).toBeLessThan(0.34);
    expect((partway - from) / (to - from)).toBeGreaterThan(0.1);
  });

  it('gives out its card, EEPROM and start count, and takes them back in a new machine', () => {
    const m = powerUp();
    ask(m, 'M850 bed.x 300');
    ask(m, 'M500');
    const card = m.card();
    expect(card.map(([name]) => name)).toContain('CONFIG.TXT');
    const eeprom = m.eeprom();
    const starts = m.starts;
    const n = powerUp();
    for (const [name, text] of card) n.putFile(name, text);
    n.setEeprom(eeprom);
    n.starts = starts;
    n.reset(true);
    n.run(200_000);
    expect(n.sent(0)).toContain('start');
    expect(ask(n, 'M850 bed.x')[0]).toBe('M850 bed.x 300');
    expect(n.starts).toBe(starts + 1);
    expect(n.card()).toEqual(card);
  });

  it('refuses a time that is not a whole 32-bit count of microseconds', () => {
    const m = powerUp();
    expect(() => m.run(-1)).toThrow(RangeError);
    expect(() => m.run(2 ** 32)).toThrow(RangeError);
  });
});
