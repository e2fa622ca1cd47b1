import { describe, expect, it } from 'vitest';
import { machineFinding, machineNow } from './machine-finding';

const E30 = { code: 30, message: 'printhead not responding', atMs: 0 };
const E31 = { code: 31, message: 'over-temperature T3 56.0 (soft limit)', atMs: 0 };
const E32 = { code: 32, message: 'temperature sensor fault T2', atMs: 0 };
const well = { faults: [], printheadAnswers: true, hot: [] };
const LIMITS = [55, 55, 55, 55, 45, 50];

describe("the dry run's machine line", () => {
  it('is red for a silent printhead, whether reported or found by asking', () => {
    expect(machineFinding({ ...well, printheadAnswers: false })).toEqual({ check: 'machine', level: 'error', message: 'E30 printhead not responding. The printer would refuse the job: clear the fault first' });
  });

  it('judges an over-temperature by the readings: still hot is an error, cooled is fine', () => {
    expect(machineFinding({ ...well, faults: [E31], hot: ['T3 56.0 °C (limit 55 °C)'] })).toEqual({
      check: 'machine',
      level: 'error',
      message: 'T3 56.0 °C (limit 55 °C) is still too hot. The printer would refuse the job: clear the fault first',
    });
    expect(machineFinding({ ...well, faults: [E31] }).level).toBe('ok');
  });

  it('warns of a sensor fault it cannot see clear', () => {
    expect(machineFinding({ ...well, faults: [E32] })).toEqual({ check: 'machine', level: 'warning', message: 'the printer reported E32 temperature sensor fault T2: it refuses the job while that stands' });
  });

  it('is green for a machine without faults', () => {
    expect(machineFinding(well)).toEqual({ check: 'machine', level: 'ok', message: 'the printhead answers, and the machine reports no fault' });
  });
});

describe('the machine as its reports left it (read live while the question is open)', () => {
  it('has a silent printhead while E30 stands, and an answering one once it is dropped', () => {
    expect(machineNow([E30], null, LIMITS).printheadAnswers).toBe(false);
    expect(machineNow([], null, LIMITS).printheadAnswers).toBe(true);
    expect(machineFinding(machineNow([E30], null, LIMITS)).level).toBe('error');
    expect(machineFinding(machineNow([], null, LIMITS)).level).toBe('ok');
  });

  it('names the sensors at or over their soft limit from the last readings', () => {
    expect(machineNow([E31], [250, 250, 250, 560, 250, 250], LIMITS).hot).toEqual(['T3 56.0 °C (limit 55 °C)']);
    expect(machineNow([E31], [250, 250, 250, 549, 250, 250], LIMITS).hot).toEqual([]); // cooled under it: the job may go
    expect(machineNow([], null, LIMITS).hot).toEqual([]); // no readings yet: nothing known hot
  });
});
