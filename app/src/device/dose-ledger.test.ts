// The dose ledger folds the Mega's DOSE: lines, as the firmware prints them, stop by stop.
import { describe, expect, it } from 'vitest';

import { parseReply, type DoseReport } from '../protocol/dialect-reply';
import { DoseLedger } from './dose-ledger';

function dose(line: string): DoseReport {
  const r = parseReply(line);
  if (r?.kind !== 'dose') throw new Error(`not a dose line: ${line}`);
  return r;
}

describe('DoseLedger', () => {
  it('counts a stop once, with what the head gave', () => {
    const l = new DoseLedger();
    l.add(dose('DOSE:stop=0 prog=0 exp=1 on=0,306353,227765,82980'));
    expect(l.delivered(0)).toEqual([0, 306353, 227765, 82980]);
    expect(l.stop(0)?.planUs).toBeUndefined();
    expect(l.delivered(1)).toBeUndefined();
    expect(l.summary()).toEqual({ stops: 1, twice: [], cutOnly: [] });
  });

  it('sums a pass on the move over its programs', () => {
    const l = new DoseLedger();
    l.add(dose('DOSE:stop=2 prog=0 exp=5 on=100,0,30,0'));
    l.add(dose('DOSE:stop=2 prog=1 exp=5 on=50,7,0,0'));
    expect(l.delivered(2)).toEqual([150, 7, 30, 0]);
    expect(l.stop(2)?.planUs).toBeUndefined();
    expect(l.stop(2)?.programs.size).toBe(2);
  });

  it('keeps a cut stop apart, counts its light again once, and marks it lit twice', () => {
    const l = new DoseLedger();
    l.add(dose('DOSE:stop=1 prog=0 exp=2 on=127,127,0,0 plan=309020,159765,0,0 cut=1'));
    expect(l.summary()).toEqual({ stops: 0, twice: [], cutOnly: [1] });
    expect(l.stop(1)?.planUs).toEqual([309020, 159765, 0, 0]);
    l.add(dose('DOSE:stop=1 prog=0 exp=3 on=309020,159765,0,0 again=1'));
    expect(l.delivered(1)).toEqual([309020, 159765, 0, 0]);
    expect(l.stop(1)?.cutUs).toEqual([[127, 127, 0, 0]]);
    expect(l.summary()).toEqual({ stops: 1, twice: [1], cutOnly: [] });
  });

  it('marks a stop whose exposure again came without its cut light (a printhead that lost power)', () => {
    const l = new DoseLedger();
    l.add(dose('DOSE:stop=4 prog=0 exp=1 on=10,0,0,0 again=1'));
    expect(l.summary().twice).toEqual([4]);
    l.clear();
    expect(l.summary()).toEqual({ stops: 0, twice: [], cutOnly: [] });
  });

  it('starts again with a new job, and keeps a job that continues or resumes', () => {
    const l = new DoseLedger();
    l.job('running', 'A.UVJ', 0);
    l.add(dose('DOSE:stop=0 prog=0 exp=1 on=1,0,0,0'));
    l.job('paused', 'A.UVJ', 1);
    l.job('running', 'A.UVJ', 1);
    expect(l.summary().stops).toBe(1);
    l.job('running', 'A.UVJ', 3);  // resumed after a reset: the same job
    expect(l.summary().stops).toBe(1);
    l.job('done', 'A.UVJ', 4);
    l.job('running', 'A.UVJ', 0);  // the same file run again
    expect(l.summary().stops).toBe(0);
    l.add(dose('DOSE:stop=0 prog=0 exp=2 on=1,0,0,0'));
    l.job('running', 'B.UVJ', 0);
    expect(l.file).toBe('B.UVJ');
    expect(l.summary().stops).toBe(0);
  });
  it('lists the stops of its lines from any line on, and counts its clears', () => {
    const l = new DoseLedger();
    l.add(dose('DOSE:stop=0 prog=0 exp=1 on=1,0,0,0'));
    l.add(dose('DOSE:stop=2 prog=0 exp=2 on=1,0,0,0'));
    l.add(dose('DOSE:stop=2 prog=1 exp=2 on=1,0,0,0'));
    expect(l.since(1)).toEqual({ stops: [2, 2], lines: 3, clears: 0 });
    expect(l.stop(2)?.lines).toBe(2);
    l.clear();
    expect(l.since(0)).toEqual({ stops: [], lines: 0, clears: 1 });
  });
});
