// The delivered dose in the work worker: the page's ledger sent a batch at a time, and the map the
// worker answers, against the map counted on the ledger itself.
import { describe, expect, it, vi } from 'vitest';

import { DoseLedger } from '../device/dose-ledger';
import { testPattern } from '../device/test-pattern';
import { batchSince, NOTHING_HEARD, type Heard } from '../job/dose-batch';
import { doseImage } from '../job/dose-colours';
import { deliveredMap, type DoseMapView } from '../job/dose-map';
import { planDoses, recordOf } from '../job/dose-plan';
import { parseReply } from '../protocol/dialect-reply';
import { DEFAULT_CONFIG, motionOf } from '../studio/machine-config';
import { answer } from './answer';

const job = testPattern(4000);
const machine = motionOf(DEFAULT_CONFIG);
const plan = planDoses(job, machine);
const noop = () => {};

/** Stops from … to as the head reports a whole F, each at `part` of its plan. */
function report(l: DoseLedger, from: number, to: number, part = (_s: number) => 1): void {
  for (let s = from; s < to; s++) {
    const r = parseReply(`DOSE:stop=${s} prog=0 exp=${s + 1} on=${recordOf(plan, s).ledUs.map((us) => Math.round(us * part(s))).join(',')}`);
    if (r?.kind !== 'dose') throw new Error('not a dose line');
    l.add(r);
  }
}

/** What the page does: the batch since the worker last heard, and the worker's answer. */
async function ask(l: DoseLedger, heard: Heard): Promise<{ map: DoseMapView; heard: Heard }> {
  const next = batchSince(l, heard);
  const { result, transfer } = await answer({ kind: 'dose-map', batch: structuredClone(next.batch), maxSide: 480 }, noop);
  expect(transfer).toEqual([(result as DoseMapView).image.pixels.buffer]);
  return { map: result as DoseMapView, heard: next.heard };
}

/** The worker's map against the map counted on the ledger itself: its words and its pixels. */
function expectSame(view: DoseMapView, l: DoseLedger): void {
  const m = deliveredMap(plan, l);
  expect([view.counts, view.twiceSteps, view.cutSteps, view.worst, view.steps]).toEqual([m.counts, m.twiceSteps, m.cutSteps, m.worst, m.steps]);
  expect(Array.from(view.image.pixels)).toEqual(Array.from(doseImage(m, 480).pixels));
}

describe('the delivered dose, counted in the work worker', () => {
  it('keeps the plan and gives the page only its shape', async () => {
    const { result } = await answer({ kind: 'dose-plan', job, machine }, noop);
    expect(result).toEqual({ cols: plan.cols, rows: plan.rows, unit: plan.unit, steps: plan.steps });
  });

  it('follows the ledger batch by batch, a clear (another job) included, as a count on the ledger would', async () => {
    await answer({ kind: 'dose-plan', job, machine }, noop);
    const l = new DoseLedger();
    let heard = NOTHING_HEARD;
    const off: Record<number, number> = { 4: 0.9, 11: 0 };
    for (let s = 0; s < plan.steps; s += 7) {
      report(l, s, Math.min(s + 7, plan.steps), (t) => off[t] ?? 1);
      const r = await ask(l, heard);
      heard = r.heard;
      expectSame(r.map, l);
    }
    expect(batchSince(l, heard).batch.stops).toEqual([]); // nothing new: an empty batch
    l.clear();
    report(l, 0, 3);
    const r = await ask(l, heard);
    expect(r.map.counts.within).toBe(new Set([0, 1, 2].flatMap((s) => recordOf(plan, s).cell)).size);
    expectSame(r.map, l);
  });

  it('hears the whole ledger again after its worker ended, and counts it afresh for the next job planned', async () => {
    const l = new DoseLedger();
    report(l, 0, plan.steps, (t) => (t === 2 ? 0.5 : 1));
    await answer({ kind: 'dose-plan', job, machine }, noop); // a fresh plan: its tally has counted nothing
    const r = await ask(l, NOTHING_HEARD);
    expect(r.map.counts.off).toBe(recordOf(plan, 2).cell.length);
    expectSame(r.map, l);
  });

  it('refuses a map before any job is planned in its worker, with words', async () => {
    vi.resetModules(); // a fresh worker's module: nothing kept
    const { doseMapNow } = await import('./dose-work');
    expect(() => doseMapNow({ clears: 0, stops: [] }, 480)).toThrow('no job is planned for its delivered dose yet');
  });
});
