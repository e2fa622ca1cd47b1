import { describe, expect, it } from 'vitest';
import type { PrintJob } from '../protocol/job-types';
import { dryRun, sidesFinding } from './dry-run';
import { DEFAULT_CONFIG } from './machine-config';

function job(over: Partial<PrintJob> = {}, cols = 20, rows = 8, value = 255): PrintJob {
  return {
    grid: { cols, rows },
    pitchUm: { x: 50, y: 50 },
    originUm: { x: 10000, y: 10000 },
    dose: { map: 'linear', fullUs: 4000 },
    leds: { offsets: [[0, 0], [0, 1], [0, 2], [0, 3]] },
    strategy: { name: 'serpentine' },
    gridData: Array.from({ length: rows }, () => new Array(cols).fill(value)),
    ...over,
  };
}
const levels = (r: ReturnType<typeof dryRun>) => Object.fromEntries(r.findings.map((f) => [f.check, f.level]));

describe('dry run', () => {
  it('passes a small job on the bed', () => {
    const r = dryRun(job(), DEFAULT_CONFIG);
    expect(levels(r)).toEqual({ envelope: 'ok', dose: 'ok', thermal: 'ok' });
    expect(r.plan.count).toBeGreaterThan(0);
  });

  it('stops a job that runs off the bed', () => {
    const r = dryRun(job({ originUm: { x: 199_500, y: 10_000 } }), DEFAULT_CONFIG);
    expect(levels(r).envelope).toBe('error');
    expect(r.findings[0].message).toMatch(/off the 200 × 200 mm bed/);
  });

  it('stops a drawing with an object cut by the bed\'s edge, naming it, until the cut is accepted', () => {
    const cut = { id: 4, name: 'picture board.png', overhangMm: { left: 0, right: 12, top: 0, bottom: 0 }, lost: 300, lit: 800 };
    const stopped = dryRun(job(), DEFAULT_CONFIG, { cuts: [cut] });
    expect(levels(stopped).clipping).toBe('error');
    expect(stopped.findings.find((f) => f.check === 'clipping')!.message).toMatch(/^picture board\.png: 12 mm past the right edge; 38 % of its exposed cells are off the bed\. .*accept the cut/);
    expect(levels(stopped).envelope).toBe('ok'); // the cut part is not in the job: the head stays on the bed
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { cuts: [cut], acceptCuts: true })).clipping).toBe('warning');
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { cuts: [] })).clipping).toBe('ok');
  });

  it('exposes a two-sided board one side at a time, and says which', () => {
    const board = (top: boolean, bottom: boolean) => ({ name: 'demo', sides: [{ id: 1, name: 'demo', side: 'top' as const, inJob: top }, { id: 2, name: 'demo (bottom)', side: 'bottom' as const, inJob: bottom }] });
    expect(sidesFinding([])).toBeNull();
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { boards: [] })).sides).toBeUndefined();
    const both = dryRun(job(), DEFAULT_CONFIG, { boards: [board(true, true)] }).findings.find((f) => f.check === 'sides')!;
    expect(both).toEqual({ check: 'sides', level: 'error', message: 'board demo: both sides are in the job, exposed on top of each other. A board is exposed one side at a time: leave one out' });
    expect(sidesFinding([board(true, false)])).toEqual({ check: 'sides', level: 'ok', message: 'the top side of board demo. The other side is left out, for once the board is turned over' });
    expect(sidesFinding([board(false, true)])!.message).toBe('the bottom side of board demo. The other side is left out, for once the board is turned over');
    expect(sidesFinding([board(false, false)])!.message).toBe('no side of board demo. The other side is left out, for once the board is turned over');
  });

  it('prices a photo scanned at the printhead link speed the printer reports: slower at 115200', () => {
    // Every cell a different gray: each LED switches twice a window, so the link's bytes set the pace.
    const photo = job({ strategy: { name: 'scan' }, dose: { map: 'linear', fullUs: 2000 }, pitchUm: { x: 100, y: 100 } }, 200, 8);
    photo.gridData = photo.gridData.map((row, r) => Array.from({ length: row.length }, (_, c) => 1 + ((c * 97 + r * 31) % 253)));
    const raised = dryRun(photo, DEFAULT_CONFIG, { linkBaud: 250000 });
    const slow = dryRun(photo, DEFAULT_CONFIG, { linkBaud: 115200 });
    expect(dryRun(photo, DEFAULT_CONFIG).plan.estimateUs).toBe(raised.plan.estimateUs); // BOARD_LINK_BAUD when the printer does not say
    expect(slow.plan.estimateUs).toBeGreaterThan(raised.plan.estimateUs);
  });

  it('stops an exposure longer than the printhead takes', () => {
    const r = dryRun(job({ dose: { map: 'linear', fullUs: 12_000_000 } }), DEFAULT_CONFIG);
    expect(levels(r).dose).toBe('error');
  });

  it('forecasts a pause at a soft limit, and the paced run that avoids it', () => {
    const hot = dryRun(job({ dose: { map: 'linear', fullUs: 800_000 } }, 24, 16), DEFAULT_CONFIG);
    expect(levels(hot).thermal).toBe('warning');
    expect(Math.max(...hot.duty)).toBeGreaterThan(0.5);
    expect(hot.thermal.pause?.sensor).toBe(4); // the driver: every lit LED warms it
    expect(hot.findings.at(-1)!.message).toMatch(/^T4 would reach its 50 °C soft limit 0:00:\d\d in, at stop \d+ of \d+: the job would pause there to cool\. Paced, it waits/);
    expect(hot.paced?.pause).toBeNull();
    expect(hot.paced!.totalUs).toBeGreaterThan(hot.plan.estimateUs);
    expect(Math.max(...hot.paced!.peakC.map((c, i) => c - [55, 55, 55, 55, 50, 50][i]))).toBeLessThan(0);
  });

  it('starts from the head as it is: a warm head pauses a job a cool one runs through', () => {
    const long = job({ dose: { map: 'linear', fullUs: 100_000 } }, 24, 16);
    expect(levels(dryRun(long, DEFAULT_CONFIG)).thermal).toBe('ok');
    const warm = dryRun(long, DEFAULT_CONFIG, { startC: [54, 54, 54, 54, 49, 30] });
    expect(warm.thermal.pause).not.toBeNull();
  });

  it('counts stops from 1: a head already at its limit pauses "at stop 1", never "stop 0" (issue 29, item 14)', () => {
    const long = job({ dose: { map: 'linear', fullUs: 2_000_000 } }, 24, 16);
    const hot = dryRun(long, DEFAULT_CONFIG, { startC: [54.8, 54.8, 54.8, 54.8, 49.8, 30] });
    expect(hot.thermal.pause?.stop).toBe(0);
    const message = hot.findings.find((f) => f.check === 'thermal')!.message;
    expect(message).toMatch(/at stop 1 of \d+:/);
    expect(message).not.toMatch(/stop 0 of/);
  });

  it('says when pacing cannot help: one stop alone heats past the limit', () => {
    const r = dryRun(job({ dose: { map: 'linear', fullUs: 9_000_000 } }, 4, 4), DEFAULT_CONFIG, { startC: [45, 45, 45, 45, 40, 25] });
    expect(r.paced?.pause).not.toBeNull();
    expect(r.findings.at(-1)!.message).toMatch(/pacing cannot prevent it .*lower the dose$/);
  });

  it('warns about a job off the mesh', () => {
    const mesh = { nx: 3, ny: 3, x0: 50_000, y0: 50_000, dx: 50_000, dy: 50_000, z: [[0, 0, 0], [0, 0, 0], [0, 0, 0]] };
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { leveling: true, mesh })).mesh).toBe('warning');
    expect(levels(dryRun(job({ originUm: { x: 60_000, y: 60_000 } }), DEFAULT_CONFIG, { leveling: true, mesh })).mesh).toBe('ok');
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { leveling: true, mesh: null })).mesh).toBe('warning');
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { leveling: false, mesh })).mesh).toBe('ok'); // one height: nothing to cover
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { leveling: null, mesh })).mesh).toBeUndefined(); // the printer did not say
  });
});

describe("the machine's faults in the dry run", () => {
  const E30 = { code: 30, message: 'printhead not responding', atMs: 0 };
  const well = { faults: [], printheadAnswers: true, hot: [] };

  it('is the first line, red for a silent printhead (job/machine-finding.test.ts has its other verdicts)', () => {
    const r = dryRun(job(), DEFAULT_CONFIG, { machine: { ...well, faults: [E30], printheadAnswers: false } });
    expect(r.findings[0]).toEqual({ check: 'machine', level: 'error', message: 'E30 printhead not responding. The printer would refuse the job: clear the fault first' });
  });

  it('is a green line for a machine without faults, and absent when not asked', () => {
    expect(levels(dryRun(job(), DEFAULT_CONFIG, { machine: well }))).toEqual({ machine: 'ok', envelope: 'ok', dose: 'ok', thermal: 'ok' });
    expect(levels(dryRun(job(), DEFAULT_CONFIG)).machine).toBeUndefined();
  });
});
