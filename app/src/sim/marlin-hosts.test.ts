// The simulated Mega as Marlin hosts (OctoPrint, Pronterface) see it: refusals, waiting for the queue,
// moves at a modal feed rate, M84 after the moves, M117 alone, the busy interval, temperatures, and a
// reset when a host opens the port.
import { describe, expect, it } from 'vitest';
import { parseReply } from '../protocol/dialect-reply';
import { SimHost } from './sim-host.fixture';

describe('Marlin hosts: refusals and faults', () => {
  it('answers refusals with echo: and leaves the machine as it was', () => {
    const h = new SimHost();
    expect(h.cmd('G0 X10')[0]).toBe('echo:E14 axis not homed: X');
    expect(h.cmd('M104 S200')[0]).toBe('echo:E10 unknown command: M104');
    h.cmd('G28');
    expect(h.cmd('G0 X9999')[0]).toBe('echo:E15 target outside soft limits: X');
    expect(h.cmd('M114')[0]).toMatch(/^X:0\.000 Y:0\.000 Z:0\.000/); // the head stayed
    h.cmd('M84'); // a cancel script's M84 releases the motors and so the homing
    expect(h.cmd('G0 X10')[0]).toBe('echo:E14 axis not homed: X');
  });

  it('keeps Error: for faults: a halted machine says so to every line', () => {
    const h = new SimHost();
    h.cmd('M112');
    expect(h.cmd('M105')[0]).toBe('Error:E13 machine halted: send M999');
  });
});

describe('Marlin hosts: waiting for the motion queue', () => {
  it('M400 answers only when the last move has ended, so M114 reports where the head stopped', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('G0 X100 Y50 F3000');
    const start = h.sim.clock.now;
    expect(h.cmd('M400').at(-1)).toMatch(/^ok/);
    expect(h.sim.clock.now - start).toBeGreaterThan(1_000_000); // 111 mm at 50 mm/s
    expect(h.cmd('M114')[0]).toMatch(/^X:100\.000 Y:50\.000 /);
  });

  it('G4 waits for the moves before it, then dwells', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('G0 X100 F6000'); // 1 s and more with acceleration
    const start = h.sim.clock.now;
    h.cmd('G4 P100');
    const took = h.sim.clock.now - start;
    h.cmd('G0 X0 F6000');
    const moveStart = h.sim.clock.now;
    h.cmd('M400');
    const move = h.sim.clock.now - moveStart;
    expect(took).toBeGreaterThanOrEqual(move + 100_000 - 2000); // the move's time and the dwell, to the ms the host steps
    expect(h.cmd('G4 S4294.968')[0]).toBe('echo:E11 bad or missing parameter: S');
  });

  it('G28 finishes the moves queued before it', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('G0 X150 F6000');
    h.cmd('G28 Y');
    expect(h.cmd('M114')[0]).toMatch(/^X:150\.000 Y:0\.000 /);
  });
});

describe('Marlin hosts: moves as Marlin makes them', () => {
  /** Virtual µs from the command's send to its ok. */
  const timed = (h: SimHost, body: string) => {
    const start = h.sim.clock.now;
    h.cmd(body);
    return h.sim.clock.now - start;
  };

  it('keeps the feed rate for every later G0/G1 until the next F, even an F alone on its line', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('G1 X40 Y30 F600'); // 10 mm/s: X's 40 mm set the time
    expect(timed(h, 'M400')).toBeGreaterThan(3_900_000);
    h.cmd('G1 X70 Y30'); // no F: still 10 mm/s, 3 s (at travel speed about 0.4 s)
    const kept = timed(h, 'M400');
    expect(kept).toBeGreaterThan(2_900_000);
    expect(kept).toBeLessThan(3_200_000);
    h.cmd('G0 X40'); // G0 shares G1's feed rate, as in Marlin
    expect(timed(h, 'M400')).toBeGreaterThan(2_900_000);
    h.cmd('G1 F6000'); // F alone is kept too: 100 mm/s
    h.cmd('G1 X70');
    expect(timed(h, 'M400')).toBeLessThan(1_000_000);
    expect(h.cmd('M114')[0]).toMatch(/^X:70\.000 Y:30\.000 /);
  });

  it('keeps the feed rate it had when a move is refused', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('G1 X10 F600');
    expect(h.cmd('G1 X9999 F6000')[0]).toBe('echo:E15 target outside soft limits: X');
    expect(h.cmd('G1 X20 F0')[0]).toBe('echo:E11 bad or missing parameter: F');
    h.cmd('M400');
    h.cmd('G1 X40');
    expect(timed(h, 'M400')).toBeGreaterThan(2_900_000);
  });

  it('forgets the feed rate at M112, as a reset of Marlin does: the configured speed again', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('G1 X10 F60');
    h.cmd('M112');
    h.cmd('M999');
    h.cmd('G28');
    h.cmd('G1 X50');
    expect(timed(h, 'M400')).toBeLessThan(1_500_000);
  });

  it('M84 and M18 finish the queued moves before releasing the motors', () => {
    for (const release of ['M84', 'M18']) {
      const h = new SimHost();
      h.cmd('G28');
      h.cmd('G1 X150 Y150 F6000');
      h.cmd(release);
      h.cmd('M400');
      expect(h.cmd('M114')[0], release).toMatch(/^X:150\.000 Y:150\.000 /);
      expect(h.cmd('G1 X10')[0], release).toBe('echo:E14 axis not homed: X');
    }
  });

  it('M117 alone clears the message', () => {
    const h = new SimHost();
    const shown = () => h.sim.module.display().some((row) => row.includes('UVP-1A2B'));
    h.cmd('M117 UVP-1A2B');
    h.sim.advance(1000); // the panel redraws
    expect(shown()).toBe(true);
    expect(h.cmd('M117')).toHaveLength(1); // just its ok
    h.sim.advance(1000);
    expect(shown()).toBe(false);
    expect(h.cmd('M850')[0]).toBe('echo:E11 bad or missing parameter'); // M850 still needs its key
  });
});

describe('Marlin hosts: link commands', () => {
  it('M113 sets the busy: interval, 0 turns it off', () => {
    const h = new SimHost();
    expect(h.cmd('M113')[0]).toBe('echo:M113 S2');
    h.cmd('M113 S5');
    h.cmd('G28');
    const busy = (from: number) => h.lines.slice(from).filter((l) => l.startsWith('busy:')).length;
    let from = h.lines.length;
    h.cmd('G4 S11');
    expect(busy(from)).toBe(2); // at 5 s and 10 s
    h.cmd('M113 S0');
    from = h.lines.length;
    h.cmd('G4 S5');
    expect(busy(from)).toBe(0);
    expect(h.cmd('M113 S61')[0]).toMatch(/^echo:E11/);
  });

  it('reports temperatures as one T: and the sensors as S0-S5, none with a target: no host shows a limit as one', () => {
    const h = new SimHost();
    const line = h.cmd('M105')[0];
    expect(line).toMatch(/^T:\d+\.\d \/0\.0( S[0-5]:\d+\.\d \/0\.0){6}$/);
    const r = parseReply(line);
    expect(r?.kind === 'temps' && r.deciC.length).toBe(6);
    // The soft limits are where a host that wants them reads them: the config.
    expect(h.cmd('M503')).toEqual(expect.arrayContaining(['M850 thermal.limit.0 55', 'M850 thermal.limit.5 50']));
  });

  it('M108 is accepted: nothing heats, so there is no wait to break', () => {
    const h = new SimHost();
    expect(h.cmd('M108')).toHaveLength(1);
  });
});

describe('a host opening the port resets the Mega', () => {
  it('clears a halt and the Mega RAM, keeps the card, and leaves no old timer running', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('M155 S1');
    h.cmd('M28 KEEP.gco');
    h.cmd('G0 X1');
    h.cmd('M29');
    h.cmd('M112');
    expect(h.cmd('M105')[0]).toMatch(/^Error:E13/);
    const boot = h.sim.boots;
    h.sim.resetMega();
    h.waitFor(/^start$/, 1000, false);
    h.reconnect();
    expect(parseReply(h.cmd('M105')[0])?.kind).toBe('temps');
    expect(h.cmd('G0 X1')[0]).toMatch(/^echo:E14/); // homing is RAM: gone
    expect(h.sim.boots).toBe(boot); // the Nano ran on
    const from = h.lines.length;
    h.sim.advance(3000);
    expect(h.lines.slice(from).filter((l) => l.startsWith('T:'))).toHaveLength(0); // the old M155 died with the old Mega
    expect(h.cmd('M20')).toContain('KEEP.gco 6');
  });
});
