// The one rule for what may be done to the machine now: from the job's and the machine's state, which
// actions are open, and why the others are not. Every control that moves, fires or uploads reads it.

import type { Printer } from '../device/connection.svelte';
import type { Fault, JobProgress } from '../device/device-state';
import { limitsOf } from '../studio/machine-config';

/** What the machine is doing, as far as the app can tell: each phase closes its own actions. */
export type MachinePhase =
  | 'disconnected'
  | 'idle'
  | 'faulted'
  | 'homing'
  | 'probing'
  | 'configuring'
  | 'resuming'
  | 'uploading'
  | 'running'
  | 'cooling'
  | 'paused';

export interface MachineView {
  connected: boolean;
  job: JobProgress | null;
  /** G28 lines sent and not answered yet. */
  homing: boolean;
  /** The probe at work: a mesh being probed (M401, G29, M402), a test touch, a deploy, stow or alarm reset. */
  probing: boolean;
  /** Settings being set, saved or reset (M850 with a value, M500, M501, M502), then read back. */
  configuring: boolean;
  /** An interrupted job being resumed: the machine homes, then runs it on. */
  resuming: boolean;
  uploading: boolean;
  /** The faults the machine still has (DeviceState.activeFaults). */
  faults: readonly Fault[];
  /** The sensors at or over their soft limit, in words: "T3 56.0 °C (limit 55 °C)". */
  hot: readonly string[];
  /** A job a restart interrupted is offered for resuming. */
  interrupted: boolean;
}

export const ACTIONS = [
  'expose', // expose the drawing or the test pattern: the dry run, then the question
  'frame', // trace the drawing's bounds, LEDs off
  'home',
  'move', // jog, go to
  'release', // motors off
  'selfTest',
  'probe', // deploy, stow, alarm reset, a test touch
  'mesh', // probe the bed, leveling on and off
  'settings', // apply, save to the card, factory defaults: an idle machine only
  'flash', // the Firmware view's Flash: never under a job, a homing or the probe
  'pause',
  'continue',
  'continuePaced',
  'stop',
  'resume', // an interrupted job
  'discard',
] as const;
export type Action = (typeof ACTIONS)[number];

export type Gate = { open: true; why?: undefined } | { open: false; why: string };
export type Actions = Record<Action, Gate>;

const OPEN: Gate = { open: true };
const closed = (why: string): Gate => ({ open: false, why });

export function phaseOf(v: MachineView): MachinePhase {
  if (!v.connected) return 'disconnected';
  if (v.resuming) return 'resuming';
  if (v.uploading) return 'uploading';
  if (v.job?.state === 'running') return v.job.cooling ? 'cooling' : 'running';
  if (v.job?.state === 'paused') return 'paused';
  if (v.homing) return 'homing';
  if (v.probing) return 'probing';
  if (v.configuring) return 'configuring';
  return v.faults.length ? 'faulted' : 'idle';
}

/** "T3 56.0 °C (limit 55 °C) is still too hot", or "… are still too hot" for several. */
export function stillTooHot(hot: readonly string[]): string {
  return `${hot.join(', ')} ${hot.length > 1 ? 'are' : 'is'} still too hot`;
}

const faultWords = (faults: readonly Fault[]) => faults.map((f) => `E${f.code} ${f.message}`).join('; ');

/** Why a phase keeps the machine to itself; null for the phases that leave it free. */
function busyWhy(phase: MachinePhase): string | null {
  switch (phase) {
    case 'disconnected': return 'not connected';
    case 'resuming': return 'the interrupted job is resuming: the machine homes first';
    case 'uploading': return 'a job is uploading';
    case 'running': return 'a job is running';
    case 'cooling': return 'a job is running (waiting for the head to cool)';
    case 'paused': return 'a job is paused: continue or stop it first';
    case 'homing': return 'the machine is homing';
    case 'probing': return 'the probe is at work (probing the bed takes a while)';
    case 'configuring': return 'settings are being written';
    default: return null;
  }
}

/** Every action, open or closed with its reason, for the machine as `v` shows it. */
export function actionsFor(v: MachineView): Actions {
  const phase = phaseOf(v);
  const busy = busyWhy(phase);
  const free = busy ? closed(busy) : OPEN;
  const jobOn = phase === 'running' || phase === 'cooling';
  // The probe sits on the printhead: a silent printhead cannot deploy it.
  const printhead = v.faults.find((f) => f.code === 30);
  const probe = busy ? free : printhead ? closed(`the printhead does not answer (${faultWords([printhead])})`) : OPEN;
  const idleish = phase === 'idle' || phase === 'faulted' || phase === 'homing' || phase === 'probing' || phase === 'configuring';
  // A paused job continues once the printhead answers (the app asks again until it does) and, unpaced,
  // once the head is below its limits (the readings say when), as the Mega refuses it otherwise. A paced
  // continue while hot is taken: the Mega waits for the head to cool first (mega.md "Pacing").
  const notPaused = closed(jobOn ? 'the job is running' : idleish ? 'no job is paused' : busy!);
  const silent = printhead ? closed(`the printhead is still faulted: ${faultWords([printhead])}`) : null;
  const goOn = phase !== 'paused' ? notPaused : v.hot.length ? closed(stillTooHot(v.hot)) : silent ?? OPEN;
  const goOnPaced = phase !== 'paused' ? notPaused : silent ?? OPEN;
  const noJob = closed(idleish ? 'no job is running' : busy!);
  const offer = !v.interrupted ? closed('no interrupted job') : busy ? closed(busy) : OPEN;
  return {
    expose: free, // a standing fault is the dry run's red line: the question says it, and offers no exposure
    frame: free,
    home: phase === 'homing' ? closed('the machine is homing already') : free,
    move: free,
    release: free,
    selfTest: free,
    probe,
    mesh: probe,
    settings: free,
    // Flashing restarts the board: a job, a homing or the probe would stop where it is. With no
    // printer connected, every board may be flashed.
    flash: phase === 'disconnected' ? OPEN : busy ? closed(`${busy}: flashing restarts the board`) : OPEN,
    pause: jobOn ? OPEN : phase === 'paused' ? closed('the job is paused') : noJob,
    continue: goOn,
    continuePaced: goOnPaced,
    stop: jobOn || phase === 'paused' ? OPEN : noJob,
    resume: offer,
    discard: offer,
  };
}

/** The sensors at or over their soft limit (settings, °C), in words for the user. */
export function hotSensors(deciC: readonly number[] | null, limitsC: readonly number[] | null): string[] {
  if (!deciC || !limitsC) return [];
  return deciC.flatMap((d, i) => (d >= limitsC[i] * 10 ? [`T${i} ${(d / 10).toFixed(1)} °C (limit ${limitsC[i]} °C)`] : []));
}

/** The machine as the rule sees it, from the printer's state (read inside $derived, it follows it). */
export function viewOf(printer: Printer): MachineView {
  return {
    connected: printer.connection.state === 'connected',
    job: printer.device.job,
    homing: printer.homing > 0,
    probing: printer.probing > 0,
    configuring: printer.configuring > 0,
    resuming: printer.resuming,
    uploading: printer.upload.state === 'uploading',
    faults: printer.device.activeFaults,
    hot: hotSensors(printer.device.deciC, printer.config ? limitsOf(printer.config) : null),
    interrupted: printer.interrupted !== null,
  };
}
