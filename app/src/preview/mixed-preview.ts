// The preview's model of a mixed job (planner.md "Mixed mode"): every pass, on the move or stop by
// stop (a band of stops as its passes), as scan-preview.ts draws a scan job's, so the drawing shows
// which passes scan; and the light of each, from its switch times or its stops' durations.

import type { MixedPlan, ScanPlan } from '../planner/plan';
import type { PrintJob } from '../protocol/job-types';
import { scanDoses, type ScanLine, type ScanPreview } from './scan-preview';

export function mixedPreview(job: PrintJob, mixed: MixedPlan): ScanPreview {
  const col = (um: number) => (um - job.originUm.x) / job.pitchUm.x;
  const { cols, rows } = job.grid;
  const lines: ScanLine[] = [];
  const from: number[] = [], cell: number[] = [], led: number[] = [], us: number[] = [];
  for (const p of mixed.passes) {
    from.push(cell.length);
    if (p.scan) {
      lines.push({ row: p.hy, fromCol: col(p.pass.runUpUm), toCol: col(p.pass.runOutUm), descending: p.descending });
      const d = scanDoses(job, { passes: [p.pass] } as ScanPlan);
      cell.push(...d.cell), led.push(...d.led), us.push(...d.us);
      continue;
    }
    // A band of stops (planner.md "Bands") is drawn as its passes, each row's stops in the band's order.
    const byRow = new Map<number, number[][]>();
    for (const s of p.stops) byRow.set(s[1], [...(byRow.get(s[1]) ?? []), s]);
    [...byRow.keys()].sort((a, b) => a - b).forEach((row, i) => {
      if (i > 0) from.push(cell.length);
      const stops = byRow.get(row)!.map((s) => s[0]);
      lines.push({ row, fromCol: stops[0], toCol: stops[stops.length - 1], descending: p.descending, stops });
      for (const [hx, hy, ...t] of byRow.get(row)!)
        t.forEach((tk, k) => {
          const [dx, dy] = job.leds.offsets[k];
          const r = hy + dy, c = hx + dx;
          if (tk > 0 && r >= 0 && r < rows && c >= 0 && c < cols) cell.push(r * cols + c), led.push(k), us.push(tk);
        });
    });
  }
  from.push(cell.length);
  const doses = { from: Uint32Array.from(from), cell: Uint32Array.from(cell), led: Uint8Array.from(led), us: Float64Array.from(us) };
  const first = mixed.passes.find((p) => p.scan);
  return { lines, doses, speedUmS: first?.scan ? Math.round((job.pitchUm.x * 1e6) / first.pass.windowUs) : 0, windowUs: mixed.windowUs, refused: mixed.refused };
}

/** The clock when each pass of a mixed job ends, µs, as planMixed's estimate counts it (a band's passes: when the band ends). */
export function mixedTimeline(mixed: MixedPlan): Float64Array {
  let t = 0;
  return Float64Array.from(mixed.passes.flatMap((p) => {
    t += p.scan ? p.scanUs : p.stopsUs;
    return Array<number>(p.scan ? 1 : new Set(p.stops.map((s) => s[1])).size).fill(t);
  }));
}
