// The faults the machine still has, folded from its reports: an over-temperature stands until its job
// continues or ends, a silent printhead until it answers; the log keeps them all.
import { describe, expect, it } from 'vitest';
import { parseReply } from '../protocol/dialect-reply';
import { applyReport, clearFault, emptyState, withUnits, type DeviceState } from './device-state';

function fold(s: DeviceState, ...lines: string[]): DeviceState {
  for (const line of lines) applyReport(s, parseReply(line)!, 0);
  return s;
}
const codes = (s: DeviceState) => s.activeFaults.map((f) => f.code);

describe('activeFaults', () => {
  it('keeps one of each code, the latest', () => {
    const s = fold(emptyState(), 'FAULT:E31 over-temperature T3 56.0 (soft limit)', 'FAULT:E31 over-temperature T4 51.0 (soft limit)');
    expect(s.activeFaults.map((f) => f.message)).toEqual(['over-temperature T4 51.0 °C (soft limit)']);
    expect(s.faults).toHaveLength(2);
  });

  it('drops the over-temperature when the paused job continues, paced or not', () => {
    const s = fold(emptyState(), 'JOB:running file=A.UVJ stop=3/10', 'FAULT:E31 over-temperature T3 56.0 (soft limit)', 'JOB:paused file=A.UVJ stop=3/10 reason=overtemp');
    expect(codes(s)).toEqual([31]);
    fold(s, 'JOB:running file=A.UVJ stop=3/10 paced=1');
    expect(codes(s)).toEqual([]);
    expect(s.faults).toHaveLength(1); // the log keeps it
  });

  for (const end of ['done', 'aborted', 'failed']) {
    it(`drops the over-temperature when the job ends ${end}`, () => {
      const s = fold(emptyState(), 'JOB:running file=A.UVJ stop=3/10 paced=1', 'FAULT:E31 over-temperature T3 56.0 (soft limit)', 'JOB:running file=A.UVJ stop=4/10 paced=1');
      expect(codes(s)).toEqual([31]); // still running: the job has not moved on from it
      fold(s, `JOB:${end} file=A.UVJ stop=10/10`);
      expect(codes(s)).toEqual([]);
    });
  }

  it('keeps events (a probe alarm, a failed homing) in the log only', () => {
    const s = fold(emptyState(), 'FAULT:E40 probe alarm', 'FAULT:E44 endstop not found while homing');
    expect(codes(s)).toEqual([]);
    expect(s.faults.map((f) => f.code)).toEqual([40, 44]);
  });

  it('drops a sensor fault or a refused exposure when a job runs', () => {
    const s = fold(emptyState(), 'FAULT:E32 temperature sensor fault T2', 'FAULT:E33 printhead refused an exposure');
    expect(codes(s)).toEqual([32, 33]);
    fold(s, 'JOB:running file=A.UVJ stop=0/10');
    expect(codes(s)).toEqual([]);
  });

  it('keeps a silent printhead through the job, until it is cleared', () => {
    const s = fold(emptyState(), 'JOB:running file=A.UVJ stop=3/10', 'FAULT:E30 printhead not responding', 'JOB:paused file=A.UVJ stop=3/10 reason=printhead', 'JOB:aborted file=A.UVJ stop=3/10');
    expect(codes(s)).toEqual([30]);
    expect(clearFault(s, 30)).toBe(true);
    expect(clearFault(s, 30)).toBe(false);
    expect(codes(s)).toEqual([]);
  });
});

describe('withUnits', () => {
  it('gives an over-temperature reading its °C, and leaves other faults as said', () => {
    expect(withUnits('over-temperature T3 60.2 (soft limit)')).toBe('over-temperature T3 60.2 °C (soft limit)');
    expect(withUnits('over-temperature T0 -5.0')).toBe('over-temperature T0 -5.0 °C');
    expect(withUnits('over-temperature')).toBe('over-temperature');
    expect(withUnits('printhead not responding')).toBe('printhead not responding');
    expect(withUnits('over-temperature T3 60.2 °C (soft limit)')).toBe('over-temperature T3 60.2 °C (soft limit)'); // once
  });
});
