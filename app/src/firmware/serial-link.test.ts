import { describe, expect, it } from 'vitest';
import { RESET_SETTLE_MS, SerialLink } from './serial-link';

/** A port that notes when DTR rises and when bytes are written, by the clock. */
function timedPort() {
  const log: { what: string; at: number }[] = [];
  const port = {
    readable: new ReadableStream<Uint8Array>({ start: () => {} }),
    writable: new WritableStream<Uint8Array>({ write: () => void log.push({ what: 'write', at: performance.now() }) }),
    async open() {},
    async close() {},
    async setSignals(s: { dataTerminalReady?: boolean }) {
      log.push({ what: s.dataTerminalReady ? 'dtr-up' : 'dtr-down', at: performance.now() });
    },
  };
  return { port: port as unknown as SerialPort, log };
}

describe('the reset over a serial port', () => {
  it('sends nothing for 100 ms after DTR rises: the chip is in its start-up time-out (14 CK + 65 ms) and would lose it', async () => {
    const { port, log } = timedPort();
    const link = await SerialLink.open(port, 115200);
    await link.reset();
    await link.write(Uint8Array.of(0x30, 0x20));
    const up = log.find((e) => e.what === 'dtr-up')!;
    const write = log.find((e) => e.what === 'write')!;
    expect(RESET_SETTLE_MS).toBeGreaterThanOrEqual(100);
    expect(write.at - up.at).toBeGreaterThanOrEqual(99);
    expect(log.map((e) => e.what)).toEqual(['dtr-down', 'dtr-up', 'write']);
    await link.close();
  });
});
