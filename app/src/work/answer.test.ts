import { describe, expect, it } from 'vitest';
import { GEOMETRIES, randomJob } from '../planner/test-jobs';
import type { Planned } from '../preview/plan-work';
import { DEFAULT_CONFIG, bedOf, motionOf } from '../studio/machine-config';
import type { TwoSided } from '../studio/objects/board-object';
import { answer } from './answer';
import type { DryRunSummary } from './work-types';

/** A job at the bed's right edge: a scan's run-out would leave the bed, where a scan is otherwise the fastest. */
function atTheEdge() {
  const job = randomJob(5, GEOMETRIES.adjacent, 'scan', [200, 20], 1);
  job.originUm = { x: bedOf(DEFAULT_CONFIG).bedMm.x * 1000 - 200 * 50, y: 20_000 };
  job.pitchUm = { x: 50, y: 50 };
  job.dose = { map: 'linear', fullUs: 2000 };
  return job;
}

const board = (top: boolean, bottom: boolean): TwoSided => ({ name: 'demo', sides: [{ id: 1, name: 'demo', side: 'top', inJob: top }, { id: 2, name: 'demo (bottom)', side: 'bottom', inJob: bottom }] });
const noop = () => {};

describe('the work worker carries what the main thread decided on', () => {
  const machine = motionOf(DEFAULT_CONFIG);
  const bedXUm = bedOf(DEFAULT_CONFIG).bedMm.x * 1000;

  it("plans the preview's automatic order among the scans that stay within the bed's width", async () => {
    const job = atTheEdge();
    const anyBed = (await answer({ kind: 'plan', job, machine, auto: true }, noop)).result as Planned;
    expect(anyBed.order).toBe('scan');
    const onBed = (await answer({ kind: 'plan', job, machine, auto: true, bedXUm }, noop)).result as Planned;
    expect(onBed.orders.scan).toBe(Infinity);
    expect(onBed.order).not.toBe('scan');
  });

  it("chooses the dry run's automatic order on the config's bed", async () => {
    const r = (await answer({ kind: 'dry-run', job: atTheEdge(), config: DEFAULT_CONFIG, auto: true, opts: {} }, noop)).result as DryRunSummary;
    expect(r.order).not.toBe('scan');
    expect(r.findings.find((f) => f.check === 'envelope')?.level).toBe('ok');
  });

  it("checks a two-sided board's sides in the dry run: one side a job", async () => {
    const job = randomJob(1, GEOMETRIES.adjacent, 'serpentine', [20, 8], 1);
    const sides = async (b: TwoSided) => ((await answer({ kind: 'dry-run', job, config: DEFAULT_CONFIG, auto: false, opts: { boards: [b] } }, noop)).result as DryRunSummary).findings.find((f) => f.check === 'sides');
    expect((await sides(board(true, true)))?.level).toBe('error');
    expect(await sides(board(false, true))).toEqual({ check: 'sides', level: 'ok', message: 'the bottom side of board demo. The other side is left out, for once the board is turned over' });
  });
});
