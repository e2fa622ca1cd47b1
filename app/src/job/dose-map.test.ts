// The delivered-dose map: the Mega's DOSE: lines, as the firmware prints them, against the job's records.
import { describe, expect, it } from 'vitest';

import { DoseLedger } from '../device/dose-ledger';
import { testPattern } from '../device/test-pattern';
import { parseReply } from '../protocol/dialect-reply';
import { DEFAULT_CONFIG, motionOf } from '../studio/machine-config';
import { CellDose, deliveredMap, DoseTally, doseSummary, faultedWords, grouped } from './dose-map';
import { packDosePlan, planDoses, recordOf, type DosePlan } from './dose-plan';

const job = testPattern(4000);
const plan = planDoses(job, motionOf(DEFAULT_CONFIG));
const lit = job.gridData.flatMap((row) => Array.from(row)).filter((v) => v > 0).length;

function feed(l: DoseLedger, line: string): void {
  const r = parseReply(line);
  if (r?.kind !== 'dose') throw new Error(`not a dose line: ${line}`);
  l.add(r);
}

/** Each stop's record as the head reports a whole F: its durations, scaled by `part` (1: as planned). */
function report(l: DoseLedger, p: DosePlan, from = 0, to = p.steps, part = (_s: number) => 1, flags = (_s: number) => ''): void {
  for (let s = from; s < to; s++) {
    const on = recordOf(p, s).ledUs.map((us) => Math.round(us * part(s)));
    feed(l, `DOSE:stop=${s} prog=0 exp=${s + 1} on=${on.join(',')}${flags(s)}`);
  }
}

describe('delivered-dose map', () => {
  it('counts every cell within 2 % when every stop gave its plan', () => {
    const l = new DoseLedger();
    report(l, plan);
    const m = deliveredMap(plan, l);
    expect(m.counts).toEqual({ within: lit, off: 0, dark: 0, waiting: 0, twice: 0 });
    expect(m.worst).toBe(0);
    expect(doseSummary(m)).toBe(`${grouped(lit)} cells within 2 %, 0 off, 0 never lit, 0 stops lit twice by a resume`);
    expect(faultedWords(m)).toBeNull();
  });

  it("counts a faulted stop once, from the exposure after its cut, and names it", () => {
    const l = new DoseLedger();
    report(l, plan, 0, 7);
    const cut = recordOf(plan, 7).ledUs;
    feed(l, `DOSE:stop=7 prog=0 exp=8 on=${cut.map((us) => Math.floor(us / 3)).join(',')} plan=${cut.join(',')} cut=1`);
    let m = deliveredMap(plan, l);
    expect(m.cutSteps).toEqual([7]);
    expect(faultedWords(m)).toBe(`Stop 8 of ${plan.steps}: cut short by a fault or a restart, and not exposed again yet.`);
    expect(m.counts.within + m.counts.waiting).toBe(lit); // the cut light is not counted: its cells wait
    report(l, plan, 7, plan.steps, () => 1, (s) => (s === 7 ? ' again=1' : ''));
    m = deliveredMap(plan, l);
    expect(m.counts.within).toBe(lit);
    expect(m.twiceSteps).toEqual([7]);
    const cells = recordOf(plan, 7).cell;
    expect(m.counts.twice).toBe(cells.length);
    for (const c of cells) expect([m.twice[c], m.state[c]]).toEqual([1, CellDose.Within]);
    expect(doseSummary(m)).toBe(`${grouped(lit)} cells within 2 %, 0 off, 0 never lit, 1 stop lit twice by a resume`);
    expect(faultedWords(m)).toMatch(/^Stop 8 of \d+: cut short by a fault or a restart, then exposed again from its start; its cells are counted once/);
  });

  it('marks cells more than 2 % off, cells never lit, and cells whose record has not come', () => {
    const l = new DoseLedger();
    // Stop 2 gives 3 % less, stop 3 1.5 % more, stop 4 nothing at all, and stop 5 is not reported.
    const parts: Record<number, number> = { 2: 0.97, 3: 1.015, 4: 0 };
    report(l, plan, 0, 5, (s) => parts[s] ?? 1);
    report(l, plan, 6);
    const m = deliveredMap(plan, l);
    const cellsOf = (s: number) => recordOf(plan, s).cell.length;
    expect(m.counts.off).toBe(cellsOf(2));
    expect(m.counts.dark).toBe(cellsOf(4));
    expect(m.counts.waiting).toBe(cellsOf(5));
    expect(m.counts.within).toBe(lit - cellsOf(2) - cellsOf(4) - cellsOf(5));
    for (const c of recordOf(plan, 2).cell) expect(m.state[c]).toBe(CellDose.Off);
    for (const c of recordOf(plan, 3).cell) expect(m.state[c]).toBe(CellDose.Within);
    for (const c of recordOf(plan, 4).cell) expect(m.state[c]).toBe(CellDose.Dark);
    for (const c of recordOf(plan, 5).cell) expect(m.state[c]).toBe(CellDose.Waiting);
    expect(m.worst).toBeCloseTo(0.03, 3);
    expect(doseSummary(m)).toContain(`${cellsOf(5)} not reported yet`);
    expect(doseSummary(m, true)).toContain(`${cellsOf(5)} not reported to this page`); // the job ended: it will not come
  });

  it("gives a program's cells the part of its light each LED gave", () => {
    // One pass of two programs: LED 0 lights cells 0-1 in program 0 and cell 2 in program 1.
    const p = packDosePlan(3, 1, 'pass', [[
      { ledUs: [200, 0, 0, 0], cell: [0, 1], led: [0, 0], us: [100, 100] },
      { ledUs: [150, 0, 0, 0], cell: [1, 2], led: [0, 0], us: [50, 100] },
    ]]);
    const l = new DoseLedger();
    feed(l, 'DOSE:stop=0 prog=0 exp=4 on=200,0,0,0');
    feed(l, 'DOSE:stop=0 prog=1 exp=4 on=120,0,0,0');
    const m = deliveredMap(p, l);
    expect(Array.from(m.deliveredUs)).toEqual([100, 140, 80]);
    expect(Array.from(m.state)).toEqual([CellDose.Within, CellDose.Off, CellDose.Off]);
    expect(doseSummary(m)).toBe('1 cell within 2 %, 2 off, 0 never lit, 0 passes lit twice by a resume');
  });

  it('follows the reports as they come, counting again only what changed, as one count afresh would', () => {
    const l = new DoseLedger();
    const tally = new DoseTally(plan);
    const parts: Record<number, number> = { 3: 0.9, 9: 0 };
    for (let s = 0; s < plan.steps; s += 5) {
      report(l, plan, s, Math.min(s + 5, plan.steps), (t) => parts[t] ?? 1);
      const m = tally.update(l), fresh = deliveredMap(plan, l);
      expect([m.counts, Array.from(m.state)]).toEqual([fresh.counts, Array.from(fresh.state)]);
    }
    expect(tally.update(l)).toBe(tally.update(l)); // nothing new: the same map
    l.clear(); // another job: every cell waits again
    expect(tally.update(l).counts).toEqual({ within: 0, off: 0, dark: 0, waiting: lit, twice: 0 });
    expect(tally.update(l).worst).toBe(0); // stop 3's 10 % went with its job
    report(l, plan, 0, 4);
    tally.update(l);
    l.clear(); // and again, with more lines by the next update than the ledger had before
    report(l, plan, 0, plan.steps, (t) => (t === 2 ? 0.5 : 1));
    expect(tally.update(l).counts).toEqual(deliveredMap(plan, l).counts);
    expect(tally.update(l).counts.off).toBe(recordOf(plan, 2).cell.length);
  });

  it('groups thousands with a thin space', () => {
    expect([grouped(7), grouped(12480), grouped(1234567)]).toEqual(['7', '12\u202f480', '1\u202f234\u202f567']);
  });
});
