// Benchmark harness: runs each case interleaved with its baseline, round by round, and prints medians
// and the ratio, so load on a shared machine hits both sides alike. Timing is printed, never asserted.

export interface Case {
  name: string;
  run: () => void;
}

export interface Row {
  group: string;
  name: string;
  medianMs: number;
  ratio: number;
}

function median(xs: number[]): number {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}

function time(fn: () => void): number {
  const t0 = performance.now();
  fn();
  return performance.now() - t0;
}

/** Runs baseline and cases in alternation `rounds` times after one warm-up round. */
export function compare(group: string, baseline: Case, cases: Case[], rounds = 9): Row[] {
  const all = [baseline, ...cases];
  all.forEach((c) => c.run());
  const samples = all.map(() => [] as number[]);
  for (let r = 0; r < rounds; r++) all.forEach((c, i) => samples[i].push(time(c.run)));
  const base = median(samples[0]);
  return all.map((c, i) => ({ group, name: c.name, medianMs: median(samples[i]), ratio: median(samples[i]) / base }));
}

export function printTable(rows: Row[], note = 'ratio = median time / baseline median'): void {
  let group = '';
  for (const r of rows) {
    if (r.group !== group) {
      group = r.group;
      console.log(`\n${group}  (${note})`);
    }
    console.log(`  ${r.name.padEnd(52)} ${r.medianMs.toFixed(2).padStart(9)} ms  ${r.ratio.toFixed(2).padStart(7)}x`);
  }
}
