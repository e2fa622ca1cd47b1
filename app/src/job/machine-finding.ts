// The dry run's line about the machine itself: would the printer take the job as it stands now?
// Asked once before the question (an M105 to learn whether the printhead answers), then read live
// while the question is open: a printhead that answers again, or a head that cools, opens the job.
import { OVERTEMP, PRINTHEAD_SILENT, type Fault } from '../device/device-state';
import type { Finding } from '../studio/dry-run';
import { hotSensors, stillTooHot } from './actions';

/** What the machine says of itself: its standing faults, whether the printhead answers, its hot sensors. */
export interface MachineCheck {
  faults: readonly Fault[];
  printheadAnswers: boolean;
  /** The sensors at or over their soft limit, in words (hotSensors). */
  hot: readonly string[];
}

/** The machine as its last reports left it: an E30 stands until the printhead answers an M105 again. */
export function machineNow(faults: readonly Fault[], deciC: readonly number[] | null, limitsC: readonly number[] | null): MachineCheck {
  return { faults, printheadAnswers: !faults.some((f) => f.code === PRINTHEAD_SILENT), hot: hotSensors(deciC, limitsC) };
}

/**
 * A printhead that does not answer (E30) and sensors over their soft limits are errors, as the
 * printer would refuse the job. An E31 itself is judged by the readings; a sensor fault or a refused
 * exposure (E32, E33) the app cannot see clear, so it is a warning.
 */
export function machineFinding(m: MachineCheck): Finding {
  const silent = m.printheadAnswers ? [] : ['E30 printhead not responding'];
  const errors = [...silent, ...(m.hot.length ? [stillTooHot(m.hot)] : [])];
  if (errors.length) return { check: 'machine', level: 'error', message: `${errors.join('; ')}. The printer would refuse the job: clear the fault first` };
  const others = m.faults.filter((f) => f.code !== PRINTHEAD_SILENT && f.code !== OVERTEMP);
  if (others.length) return { check: 'machine', level: 'warning', message: `the printer reported ${others.map((f) => `E${f.code} ${f.message}`).join('; ')}: it refuses the job while that stands` };
  return { check: 'machine', level: 'ok', message: 'the printhead answers, and the machine reports no fault' };
}
