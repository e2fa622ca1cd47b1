// The ESP link learns the job format its hub writes from the Mega's M115 answer, as the hub does.
import { afterEach, describe, expect, it, vi } from 'vitest';
import { EspLink } from './esp-link';

/** A hub's /ws that answers M115 with `caps` after the Mega's name, and ok. */
function fakeHub(caps: string[]) {
  return class FakeSocket {
    static readonly OPEN = 1;
    readyState = 1;
    onopen: (() => void) | null = null;
    onerror: (() => void) | null = null;
    onclose: (() => void) | null = null;
    onmessage: ((e: { data: string }) => void) | null = null;
    constructor() {
      queueMicrotask(() => this.onopen?.());
    }
    send(frame: string) {
      const m = JSON.parse(frame);
      const lines = m.line === 'M115' ? ['FIRMWARE_NAME:UVExposure 0.1.0 (Mega) PROTOCOL_VERSION:1', 'Cap:RX_WINDOW:2', ...caps, 'ok'] : ['ok'];
      queueMicrotask(() => this.onmessage?.({ data: JSON.stringify({ type: 'reply', id: m.id, lines }) }));
    }
    close() {}
  };
}

describe('EspLink', () => {
  afterEach(() => vi.unstubAllGlobals());

  it.each([
    [['Cap:JOB_FORMAT:2'], 2],
    [['Cap:JOB_FORMAT:3'], 2],
    [['Cap:JOB_FORMAT:1'], 1],
    [[], 1],
  ])('with %j in the M115 answer counts the upload in job format %i', async (caps, format) => {
    vi.stubGlobal('WebSocket', fakeHub(caps));
    const link = new EspLink('http://hub.local');
    expect(link.jobFormat).toBe(1); // before the Mega has said
    await link.open(() => {}, () => {});
    expect(link.jobFormat).toBe(format);
  });

  it.each([
    [['Cap:LINK_BAUD:115200'], 115200],
    [['Cap:JOB_FORMAT:2', 'Cap:LINK_BAUD:250000'], 250000],
    [[], null],
  ])('with %j in the M115 answer knows the printhead link speed the Mega plans at: %s', async (caps, baud) => {
    vi.stubGlobal('WebSocket', fakeHub(caps));
    const link = new EspLink('http://hub.local');
    expect(link.linkBaud).toBeNull();
    await link.open(() => {}, () => {});
    expect(link.linkBaud).toBe(baud);
  });
});
