import { describe, expect, it } from 'vitest';
import { GEOMETRIES, randomJob } from '../planner/test-jobs';
import { encodeFrame } from '../protocol/dialect-frame';
import { parseReply } from '../protocol/dialect-reply';
import { formatOk } from '../protocol/reply-format';
import { encodeJob } from '../protocol/job-encode';
import { bedZ, DEFAULT_BED } from './bed';
import { SimHost } from './sim-host.fixture';
import { SimPrinter } from './sim-printer';

function upload(h: SimHost, file: string, text: string): string[] {
  const out = [...h.cmd(`M28 ${file}`)];
  for (const record of text.trimEnd().split('\n')) out.push(...h.cmd(record));
  out.push(...h.cmd('M29'));
  return out;
}

const card = (h: SimHost) => new Map(h.sim.module.card());
/** The job's stop count, from its JOB: line. */
const stops = (h: SimHost) => Number(/stop=\d+\/(\d+)/.exec(h.cmd('M27')[0])?.[1]);

function smallJob(seed = 3) {
  const job = randomJob(seed, GEOMETRIES.adjacent, 'serpentine', [24, 12], 0.4);
  job.originUm = { x: 20000, y: 30000 };
  job.pitchUm = { x: 50, y: 50 };
  job.dose = { map: 'linear', fullUs: 4000 };
  return job;
}

describe('simulated printer: link and identity', () => {
  it('identifies itself like the Mega, window included', () => {
    const h = new SimHost();
    const block = h.cmd('M115');
    expect(parseReply(block[0])).toEqual({ kind: 'firmware', name: 'UVExposure 0.1.0 (Mega)', protocol: 1 });
    expect(block).toContain('Cap:RX_WINDOW:3');
    expect(block).toContain('Cap:LINK_BAUD:250000'); // the printhead link speed it plans jobs at: its Nano takes the raise
    expect(block.at(-1)).toBe(formatOk(1, 8, 3));
  });

  it('answers every line exactly once, errors included', () => {
    const lines: string[] = [];
    const sim = new SimPrinter((b) => lines.push(...b.split('\n').filter(Boolean)));
    sim.boot();
    sim.advance(200); // the Mega's start: what comes before it is lost, as on the board
    lines.length = 0;
    sim.receive('M999x\nG1 X1e3\nN1 M105*0\n');
    sim.advance(20);
    expect(lines.filter((l) => l.startsWith('ok'))).toHaveLength(3);
    expect(lines[0]).toBe('echo:E10 unknown command: M999x');
    expect(lines).toContain('echo:E11 bad or missing parameter');
    expect(lines).toContain('Resend: 1');
  });

  it('runs the lines queued behind a long command as soon as it ends, with no resend', () => {
    const lines: string[] = [];
    const sim = new SimPrinter((b) => lines.push(...b.split('\n').filter(Boolean)));
    sim.receive(`${encodeFrame(1, 'G28')}\n${encodeFrame(2, 'G90')}\n${encodeFrame(3, 'M114')}\n`);
    sim.advance(60_000);
    expect(lines.filter((l) => l.startsWith('ok N')).map((l) => l.split(' ')[1])).toEqual(['N1', 'N2', 'N3']);
    expect(lines).toContain('X:0.000 Y:0.000 Z:0.000 E:0.000 Count X:0 Y:0 Z:0');
  });

  it('reports six temperatures on M105 and by auto-report', () => {
    const h = new SimHost();
    expect(parseReply(h.cmd('M105')[0])?.kind).toBe('temps');
    h.cmd('M155 S1');
    const from = h.lines.length;
    h.sim.advance(3050);
    expect(h.lines.slice(from).filter((l) => l.startsWith('T:')).length).toBe(3); // one a second
  });
});

describe('simulated printer: motion', () => {
  it('refuses moves before homing, then moves in the time the model gives', () => {
    const h = new SimHost();
    expect(h.cmd('G0 X10')[0]).toBe('echo:E14 axis not homed: X');
    h.cmd('G28');
    h.cmd('G0 X10 Y20');
    h.sim.advance(1000);
    expect(h.cmd('M114')[0]).toBe('X:10.000 Y:20.000 Z:0.000 E:0.000 Count X:800 Y:1600 Z:0');
    expect(h.cmd('G0 X999')[0]).toBe('echo:E15 target outside soft limits: X');
  });

  it('jogs until M410 and reports endstops', () => {
    const h = new SimHost();
    h.cmd('G28');
    expect(h.cmd('M119')).toContain('x_min: TRIGGERED');
    h.cmd('M820 X1 S0'); // 5 mm/s
    h.sim.advance(1000);
    h.cmd('M410');
    const x = parseReply(h.cmd('M114')[0]);
    expect(x?.kind === 'position' && x.um[0]).toBeGreaterThan(3000);
    expect(x?.kind === 'position' && x.um[0]).toBeLessThan(6000);
  });

  it('runs the kinematic self-test and reports steps per axis', () => {
    const h = new SimHost();
    h.cmd('G28');
    expect(h.cmd('M822 Q')[0]).toBe('TEST:quick x=pass x_steps=1600 y=pass y_steps=1600');
    const full = h.cmd('M822');
    expect(full).toContain('TEST:full x=pass x_steps=16000 y=pass y_steps=16000');
  });
});

describe('simulated printer: probe and mesh', () => {
  it('probes the bed surface and builds a mesh of it', () => {
    const h = new SimHost();
    h.cmd('G28');
    h.cmd('G0 X50 Y60 Z5');
    expect(h.cmd('M401')).toContain('PROBE:deployed');
    // Where the pin closed, to within one of Z's steps (2.5 µm at 400 steps/mm).
    const bed = parseReply(h.cmd('G30')[0]);
    expect(bed?.kind === 'probePoint' && bed.um.slice(0, 2)).toEqual([50000, 60000]);
    expect(bed?.kind === 'probePoint' && Math.abs(bed.um[2] - bedZ(DEFAULT_BED, 50000, 60000))).toBeLessThanOrEqual(2.5);
    const block = h.cmd('G29 X3 Y3');
    expect(block.filter((l) => l.startsWith('Bed X:'))).toHaveLength(9);
    const rows = block.filter((l) => l.startsWith('MESH:row'));
    expect(rows).toHaveLength(3);
    const first = rows[0].split(' ').slice(2).map(Number);
    [10000, 100000, 190000].forEach((x, i) => expect(Math.abs(first[i] * 1000 - bedZ(DEFAULT_BED, x, 10000))).toBeLessThanOrEqual(2.5));
  });

  it('reports a probe alarm and clears it with the alarm release', () => {
    const h = new SimHost({ probeAlarm: true });
    h.cmd('G28');
    h.cmd('G0 Z5');
    const block = h.cmd('M401');
    expect(block).toContain('PROBE:alarm');
    expect(block.some((l) => l.startsWith('Error:E40'))).toBe(true);
    h.cmd('M280 P0 S160');
    expect(h.cmd('M401')).toContain('PROBE:deployed');
  });
});

describe('simulated printer: jobs', () => {
  it('stores a verified upload and refuses a corrupt one', () => {
    const h = new SimHost();
    const text = encodeJob(smallJob());
    expect(upload(h, 'A.UVJ', text)).toContain('echo:Done saving file.');
    expect(card(h).get('A.UVJ')).toBe(text);
    const broken = text.replace(/end [0-9a-f]{8}/, 'end 00000000');
    const out = upload(h, 'B.UVJ', broken);
    expect(out.some((l) => l.startsWith('echo:E24'))).toBe(true);
    expect(card(h).has('B.UVJ')).toBe(false);
    expect(h.cmd('M20')).toEqual(['Begin file list', `A.UVJ ${text.length}`, 'End file list', expect.stringMatching(/^ok/)]);
  });

  it('runs commands between an upload\'s records and refuses a plain line as a record', () => {
    const h = new SimHost();
    const text = encodeJob(smallJob(5));
    const records = text.trimEnd().split('\n');
    h.cmd('M28 C.UVJ');
    records.forEach((r, i) => {
      if (i === 3) {
        expect(h.cmd('M105')[0]).toMatch(/^T:/); // a console line between records runs
        const from = h.lines.length;
        h.sim.receive('2#3932\n'); // the tail of a line split by a damaged byte
        h.sim.advance(20);
        expect(h.lines.slice(from).find((l) => l.startsWith('Error:E4'))).toContain('a job record needs a line number');
      }
      h.cmd(r);
    });
    expect(h.cmd('M29')).toContain('echo:Done saving file.');
    expect(card(h).get('C.UVJ')).toBe(text);
  });

  it('runs a job, each stop once, in no more than the planner\'s estimate', () => {
    const h = new SimHost();
    h.cmd('G28');
    upload(h, 'J.UVJ', encodeJob(smallJob()));
    h.cmd('M23 J.UVJ');
    const fires = h.sim.module.fires;
    h.cmd('M24');
    const start = h.sim.clock.now;
    const total = stops(h);
    const remaining = Number(/remaining=(\d+)/.exec(h.cmd('M27')[0])?.[1]);
    expect(h.waitFor(/^JOB:done/)).toContain(`stop=${total}/${total}`);
    expect(h.sim.module.fires - fires).toBe(total); // every stop lights something, once
    const took = (h.sim.clock.now - start) / 1e6;
    // The estimate is whole seconds, rounded: this job's 62 stops take about 1.5 s, its estimate
    // (stop_overhead_us as measured on the real images, StopCycle) within 3 % of that.
    expect(took).toBeLessThanOrEqual(remaining + 1);
    expect(took).toBeGreaterThan((remaining - 0.5) * 0.9);
  });

  it('resumes after a power cycle with every stop exactly once', () => {
    const h = new SimHost();
    h.cmd('G28');
    upload(h, 'R.UVJ', encodeJob(smallJob(9)));
    h.cmd('M23 R.UVJ');
    const fires = h.sim.module.fires;
    h.cmd('M24');
    const total = stops(h);
    while (h.sim.module.fires - fires < total / 2) h.sim.advance(1);
    const fired = h.sim.module.fires - fires;
    h.sim.powerCycle();
    h.reconnect();
    const interrupted = h.cmd('M1000 S')[0];
    expect(interrupted).toMatch(new RegExp(`^JOB:interrupted file=R.UVJ stop=\\d+/${total}$`));
    const done = Number(/stop=(\d+)\//.exec(interrupted)?.[1]);
    expect(done).toBeGreaterThan(0);
    expect(done).toBeLessThanOrEqual(fired);
    expect(h.cmd('M1000')[0]).toMatch(/^echo:E14/); // must home first
    h.cmd('G28');
    const before = h.sim.module.fires;
    h.cmd('M1000');
    h.waitFor(/^JOB:done/);
    expect(h.sim.module.fires - before).toBe(total - done); // the rest, each once
    expect(h.cmd('M1000 S')[0]).toBe('JOB:idle');
  });

  it('pauses, continues and aborts with the LEDs off', () => {
    const h = new SimHost();
    h.cmd('G28');
    upload(h, 'P.UVJ', encodeJob(smallJob(4)));
    h.cmd('M23 P.UVJ');
    h.cmd('M24');
    h.sim.advance(500);
    h.cmd('M25');
    h.waitFor(/^JOB:paused/);
    const n = h.sim.module.fires;
    h.sim.advance(2000);
    expect(h.sim.module.fires).toBe(n);
    expect(h.sim.module.lit).toBe(0);
    h.cmd('M24');
    h.sim.advance(300);
    h.cmd('M524');
    expect(h.sim.module.lit).toBe(0);
    expect(h.cmd('M27')[0]).toMatch(/^JOB:aborted/);
    expect(h.cmd('M1000 S')[0]).toBe('JOB:idle');
  });
});

describe('simulated printer: faults', () => {
  it('heats with LED duty, and over-temperature stops the LEDs and says why', () => {
    const h = new SimHost({ thermal: { heatingCPerS: 1500 } }); // lit LEDs heat their sensors 1500 °C/s
    h.cmd('G28');
    upload(h, 'H.UVJ', encodeJob(smallJob(5)));
    h.cmd('M23 H.UVJ');
    h.cmd('M24');
    // At this rate the Nano's own cut-off comes first: it refuses the next exposure, hot (mega.md "Pacing").
    const fault = h.waitFor(/^FAULT:E3/, 120_000);
    expect(fault).toMatch(/^FAULT:E31 over-temperature (T\d \d+\.\d \(soft limit\)|T\d \d+\.\d|at stop \d+)$/);
    expect(h.sim.module.lit).toBe(0);
    expect(h.cmd('M27').find((l) => l.startsWith('JOB:'))).toMatch(/^JOB:paused .*reason=overtemp/);
    expect(h.cmd('M24')[0]).toMatch(/^Error:E31/);
  });

  it('continues a job paused hot, paced, by waiting to cool first: no second press (mega.md "Pacing")', () => {
    const h = new SimHost();
    h.cmd('G28');
    upload(h, 'W.UVJ', encodeJob(smallJob(7)));
    h.cmd('M23 W.UVJ');
    h.sim.setFaults({ overheatCPerS: 40 }); // the head heats with or without its LEDs: past 55 °C within the job
    h.cmd('M24');
    h.waitFor(/^JOB:paused .*reason=overtemp/, 120_000);
    expect(h.cmd('M24')[0]).toBe('Error:E31 over-temperature: printhead faulted'); // unpaced: refused while hot
    h.sim.setFaults({ overheatCPerS: 0 });
    expect(h.cmd('M24 P1').filter((l) => /^(Error|echo):E/.test(l))).toEqual([]);
    expect(h.waitFor(/^JOB:/, 1000)).toMatch(/^JOB:running .* paced=1 cooling=1$/);
    const fires = h.sim.module.fires;
    h.sim.advance(1000); // from 55 °C or more to 52 takes longer
    expect(h.cmd('M27')[0]).toMatch(/ cooling=1$/);
    expect(h.sim.module.fires).toBe(fires); // dark while it waits
    h.waitFor(/^JOB:running (?!.*cooling=1)/, 120_000); // the wait ends: every reading 3 °C under its limit
    for (let i = 0; i < 4; i++) expect(h.sim.thermal.temp[i], `T${i}`).toBeLessThanOrEqual(55 - 3);
    expect(h.waitFor(/^JOB:(done|paused|failed)/, 600_000)).toMatch(/^JOB:done .*paced=1/);
  });

  it('refuses to start a job while the printhead is over its limit', () => {
    const h = new SimHost({ thermal: { extraHeatingCPerS: 10 } }); // hot before any LED fires (and below the TMP36's 125 °C)
    h.cmd('G28');
    upload(h, 'C.UVJ', encodeJob(smallJob(6)));
    h.cmd('M23 C.UVJ');
    expect(h.cmd('M24')[0]).toBe('Error:E31 over-temperature: printhead faulted');
    expect(h.sim.module.fires).toBe(0);
  });

  it('stalls: a line sent while the printer is not reading is answered when the stall ends', () => {
    const h = new SimHost({ link: { stallEveryMs: 1000, stallMs: 300 } });
    h.sim.advance(1000 - h.sim.clock.now / 1000 + 10); // 10 ms into a stall
    const sentAt = h.sim.clock.now;
    const block = h.cmd('M105');
    expect(parseReply(block[0])?.kind).toBe('temps');
    expect(h.sim.clock.now - sentAt).toBeGreaterThanOrEqual(285_000); // held for the rest of the stall
  });

  it('reports a missing printhead', () => {
    const h = new SimHost({ missingNano: true });
    const block = h.cmd('M105'); // after the first reading's three time-outs
    expect(block).toContain('FAULT:E30 printhead not responding');
    expect(block).toContain('Error:E30 printhead not responding');
  });

  it('halts on M112 until M999', () => {
    const h = new SimHost();
    h.sim.receive(encodeFrame(99, 'M112').replace(/^N99 /, '') + '\n');
    h.sim.receive('M112\n');
    h.sim.advance(20);
    expect(h.cmd('M105')[0]).toBe('Error:E13 machine halted: send M999');
    h.cmd('M999');
    expect(parseReply(h.cmd('M105')[0])?.kind).toBe('temps');
  });
});
