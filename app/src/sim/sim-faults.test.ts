// The faults the simulated printer models, changed while it runs, as its panel changes them (issue 17, item 11).
import { describe, expect, it } from 'vitest';
import { parseReply } from '../protocol/dialect-reply';
import { encodeJob } from '../protocol/job-encode';
import { NO_FAULTS, saneFaults } from './sim-faults';
import { SimHost } from './sim-host.fixture';
import { smallJob } from './sim-store.fixture';

describe('simulated printer: faults set while it runs', () => {
  it('loses its printhead and finds it again', () => {
    const h = new SimHost();
    expect(parseReply(h.cmd('M105')[0])?.kind).toBe('temps');
    h.sim.setFaults({ missingNano: true });
    h.waitFor(/^FAULT:E30/, 5000); // three polls unanswered
    expect(h.cmd('M105')[0]).toBe('Error:E30 printhead not responding');
    h.sim.setFaults({ missingNano: false });
    h.sim.advance(1000); // the Mega's next poll finds it
    expect(parseReply(h.cmd('M105')[0])?.kind).toBe('temps');
    expect(h.sim.faults).toEqual(NO_FAULTS);
  });

  it('overheats the printhead: a running job stops with the LEDs off and says why', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.upload('H.UVJ', encodeJob(smallJob(5)));
    h.cmd('M23 H.UVJ');
    h.cmd('M24');
    h.sim.advance(50);
    h.sim.setFaults({ overheatCPerS: 200 }); // past the 55 °C soft limit in a fraction of the job's 2 s
    h.waitFor(/^FAULT:E31 over-temperature/, 10_000);
    expect(h.sim.module.lit).toBe(0);
    expect(h.cmd('M27').find((l) => l.startsWith('JOB:'))).toMatch(/^JOB:paused .*reason=overtemp/);
  });

  it('alarms the probe on its next deploy only', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.sim.setFaults({ probeAlarm: true });
    expect(h.cmd('M401')).toContain('PROBE:alarm');
    h.cmd('M280 P0 S160');
    expect(h.cmd('M401')).toContain('PROBE:deployed');
    h.cmd('M402');
    h.sim.setFaults({ overheatCPerS: 0 }); // another change does not arm it again
    expect(h.cmd('M401')).toContain('PROBE:deployed');
  });

  it('damages the link while corruption is on, and not after', () => {
    const lines: string[] = [];
    const h = new SimHost();
    h.sim.setFaults({ corruptPercent: 100 });
    h.sim.receive('M105\n');
    h.sim.advance(20);
    lines.push(...h.lines.splice(0));
    expect(lines.some((l) => l.startsWith('T:'))).toBe(false); // every byte has a bit flipped
    h.sim.setFaults({ corruptPercent: 0, dropPercent: 0 });
    h.sim.receive('\n'); // ends the damaged line, as a host's next line would
    h.sim.advance(20);
    expect(parseReply(h.cmd('M105')[0])?.kind).toBe('temps');
  });

  it('stalls from the moment stalls are set', () => {
    const h = new SimHost();
    h.sim.setFaults({ stallEveryMs: 1000, stallMs: 300 });
    h.sim.advance(1000 - ((h.sim.clock.now / 1000) % 1000) + 10); // 10 ms into a stall
    const sentAt = h.sim.clock.now;
    h.cmd('M105');
    expect(h.sim.clock.now - sentAt).toBeGreaterThanOrEqual(285_000);
  });

  it('pulled cable: the link drops, the job runs on, and opening the link again brings it back', () => {
    const h = new SimHost();
    let dropped = 0;
    h.sim.onDisconnect = () => dropped++;
    h.cmd('G28');
    h.upload('U.UVJ', encodeJob(smallJob(6)));
    h.cmd('M23 U.UVJ');
    h.cmd('M24');
    const fires = h.sim.module.fires;
    while (h.sim.module.fires - fires < 3) h.sim.advance(1);
    h.sim.unplug();
    h.sim.advance(1);
    expect(dropped).toBe(1);
    const heard = h.lines.length;
    const exposed = h.sim.module.fires;
    h.sim.advance(300);
    expect(h.lines.length).toBe(heard); // nothing passes
    expect(h.sim.module.fires).toBeGreaterThan(exposed); // the printer runs on
    h.sim.resetMega(); // a host opens the link again: DTR restarts the Mega
    h.sim.advance(1000);
    expect(dropped).toBe(1); // once: the link stays up
    expect(h.lines.at(-1)).toBe('start');
    h.reconnect();
    expect(h.cmd('M1000 S')[0]).toMatch(/^JOB:interrupted file=U\.UVJ stop=\d+\/\d+$/);
  });

  it('holds each fault to what the model takes', () => {
    expect(saneFaults({ corruptPercent: 120, dropPercent: -3, stallMs: Number.NaN, overheatCPerS: 5, missingNano: 'yes' as unknown as boolean })).toEqual({
      ...NO_FAULTS,
      corruptPercent: 100,
      overheatCPerS: 5,
    });
  });
});
