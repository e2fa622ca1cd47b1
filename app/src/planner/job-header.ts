// The planner's view of a PrintJob: its header fields with defaults filled in (protocol/esp.md, job.md).

import type { JobHeader, PrintJob } from '../protocol/job-types';

export function headerOf(job: PrintJob): JobHeader {
  const d = job.dose;
  return {
    cols: job.grid.cols,
    rows: job.grid.rows,
    pitchUm: [job.pitchUm.x, job.pitchUm.y],
    originUm: [job.originUm.x, job.originUm.y],
    map: d.map,
    level: d.map === 'threshold' ? d.level ?? 128 : 0,
    ...('fullUs' in d ? { fullUs: d.fullUs } : { targetUJcm2: d.targetUJcm2, irradianceUWcm2: d.irradianceUWcm2 }),
    gainPermille: job.leds.gainPermille ?? [1000, 1000, 1000, 1000],
    thermal: [job.thermal?.coeffCentiPctPerC ?? 0, job.thermal?.refDeciC ?? 250],
    offsets: job.leds.offsets,
    strategy: job.strategy.name,
    seed: job.strategy.name === 'random' ? job.strategy.seed ?? 0 : 0,
  };
}
