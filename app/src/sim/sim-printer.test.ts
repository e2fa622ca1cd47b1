import { describe, expect, it } from 'vitest';
import { encodeFrame } from '../protocol/dialect-frame';
import { parseReply } from '../protocol/dialect-reply';
import { SimPrinter } from './sim-printer';

function harness() {
  const lines: string[] = [];
  let buf = '';
  const sim = new SimPrinter((bytes) => {
    buf += bytes;
    const parts = buf.split('\n');
    buf = parts.pop()!;
    lines.push(...parts);
  });
  return { sim, lines };
}

describe('simulated printer', () => {
  it('identifies itself like the Mega, window included', () => {
    const { sim, lines } = harness();
    sim.receive(encodeFrame(1, 'M115') + '\n');
    expect(parseReply(lines[0])).toEqual({ kind: 'firmware', name: 'UVExposure 0.1.0 (Simulated Mega)', protocol: 1 });
    expect(lines).toContain('Cap:RX_WINDOW:8');
    expect(lines.at(-1)).toBe('ok N1 P8 B8');
  });

  it('reports six temperatures on M105 and by auto-report', () => {
    const { sim, lines } = harness();
    sim.receive('M105\n');
    const temps = parseReply(lines[0]);
    expect(temps?.kind).toBe('temps');
    if (temps?.kind === 'temps') expect(temps.deciC).toHaveLength(6);
    sim.receive('M155 S1\n');
    lines.length = 0;
    sim.tick(999);
    expect(lines).toEqual([]);
    sim.tick(1000);
    expect(parseReply(lines[0])?.kind).toBe('temps');
  });

  it('answers every line exactly once, errors included', () => {
    const { sim, lines } = harness();
    sim.receive('M999\nG1 X1e3\nN1 M105*0\n');
    expect(lines.filter((l) => l.startsWith('ok'))).toHaveLength(3);
    expect(lines[0]).toBe('Error:E10 unknown command: M999');
    expect(lines[2]).toBe('Error:E11 bad or missing parameter');
    expect(lines).toContain('Resend: 1');
  });
});
