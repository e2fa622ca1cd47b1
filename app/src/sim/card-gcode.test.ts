// G-code files on the simulated card, the Marlin way: stored uploads, M20-M32, progress and the end.
import { describe, expect, it } from 'vitest';
import { encodeFrame } from '../protocol/dialect-frame';
import { CardPrint, isGcodeName } from './card-gcode';
import { SimHost } from './sim-host.fixture';

const upload = (h: SimHost, name: string, lines: string[]) => {
  h.cmd(`M28 ${name}`);
  for (const l of lines) expect(h.cmd(l)).toHaveLength(1); // stored: only its ok, nothing runs
  return h.cmd('M29');
};

describe('G-code files on the card', () => {
  it('tells G-code from jobs by the name', () => {
    expect(['a.gco', 'B.GCODE', 'c.g'].every(isGcodeName)).toBe(true);
    expect(['PCB.UVJ', 'job-3.uvj', 'gco', 'a.gc', '.g'].some(isGcodeName)).toBe(false);
  });

  it('stores an upload line by line without running it, and shows it only at M29', () => {
    const h = new SimHost();
    expect(h.cmd('M21')[0]).toBe('echo:SD card ok');
    expect(h.cmd('M28 /part.gco')[0]).toBe('echo:Writing to file: part.gco');
    h.cmd('G28');
    h.cmd('G0 X10 ; to the start');
    expect(h.cmd('M20')).toHaveLength(1); // stored too, and the file is not there yet
    expect(h.cmd('M29')[0]).toBe('echo:Done saving file.');
    expect(h.sim.mega.motion.homed).toEqual([false, false, false]); // nothing ran
    expect(h.sim.sd.files.get('part.gco')).toBe('G28\nG0 X10\nM20\n');
    expect(h.cmd('M20')).toContain('part.gco 15');
  });

  it('never keeps an upload cut short, and refuses plain lines in it', () => {
    const h = new SimHost();
    h.cmd('M28 cut.gco');
    h.sim.receive('G28\n'); // a plain line has no check: it cannot be stored
    h.sim.advance(5);
    expect(h.lines.at(-2)).toBe('Error:E4 checksum without line number: a stored line needs a line number');
    h.cmd('G0 X1');
    h.cmd('M112');
    h.cmd('M999');
    expect(h.sim.sd.find('cut.gco')).toBeUndefined();
    expect(h.cmd('M28 job~c')[0]).toBe("echo:E11 bad or missing parameter: a job's name has no ~");
  });

  it('prints a file from the card: M23, M24, progress on M27, Done printing file, then deselected', () => {
    const h = new SimHost();
    upload(h, 'run.gco', ['G28', 'G0 X20 Y10 F6000', 'G4 P10', 'G0 X30', 'M400']);
    expect(h.cmd('M23 /RUN.GCO')).toEqual(['File opened: run.gco Size: 40', 'File selected', expect.stringMatching(/^ok/)]);
    expect(h.cmd('M27')[0]).toBe('SD printing byte 0/40');
    h.cmd('M24');
    h.waitFor(/^Done printing file$/, 60_000);
    expect(h.cmd('M114')[0]).toMatch(/^X:30\.000 Y:10\.000 /);
    expect(h.cmd('M27')[0]).toMatch(/^JOB:/); // deselected: the card's jobs report again
  });

  it('pauses after the current line, rewinds with M26, and lets host lines run in between', () => {
    const h = new SimHost();
    upload(h, 'slow.gco', ['G28', 'G4 S2', 'G0 X50', 'G4 S2', 'G0 X60']);
    h.cmd('M32 slow.gco');
    h.sim.advance(500);
    expect(h.cmd('M105').find((l) => l.startsWith('T:'))).toBeDefined(); // answered while the file runs
    h.cmd('M25');
    h.sim.advance(10_000);
    const at = h.cmd('M27')[0];
    expect(at).toMatch(/^SD printing byte (\d+)\/30$/);
    expect(at).not.toBe('SD printing byte 30/30');
    h.cmd('M26 S12'); // inside "G0 X50": moves on to the next line
    expect(h.cmd('M27')[0]).toBe('SD printing byte 17/30');
    h.cmd('M24');
    h.waitFor(/^Done printing file$/, 60_000); // the last line has run; its move may still be going, as in Marlin
    h.cmd('M400');
    expect(h.cmd('M114')[0]).toMatch(/^X:60\.000 /);
  });

  it('refuses to start other files from inside a file, and refuses uploads while one runs', () => {
    const h = new SimHost();
    upload(h, 'a.gco', ['G4 S1', 'M23 a.gco', 'M117 still here']);
    h.cmd('M23 a.gco');
    h.cmd('M24');
    expect(h.cmd('M28 b.gco')[0]).toBe('echo:E12 not allowed while a job is running');
    h.sim.advance(2000);
    expect(h.lines).toContain('Done printing file');
    expect(h.lines).toContain('echo:E12 not allowed while a job is running: M23');
    expect(h.sim.mega.message).toBe('still here');
  });

  it('M524 stops a file; a fault stops it too', () => {
    const h = new SimHost();
    upload(h, 'f.gco', ['G4 S5', 'M117 never']);
    h.cmd('M32 f.gco');
    h.cmd('M524');
    h.sim.advance(10_000);
    expect(h.sim.mega.message).toBe('');
    expect(h.cmd('M27')[0]).toMatch(/^JOB:/);
  });

  it('a CardPrint reads lines without comments and blank lines', () => {
    const c = new CardPrint('x.gco', 'G28 ; home\n\n  \nG0 X1\n');
    c.running = true;
    expect([c.next(), c.next(), c.next()]).toEqual(['G28', 'G0 X1', 'end']);
    void encodeFrame;
  });
});
