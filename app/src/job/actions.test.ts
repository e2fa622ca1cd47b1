// The rule for what may be done to the machine: every action in every phase, open or closed with a reason.
import { describe, expect, it } from 'vitest';
import type { JobProgress } from '../device/device-state';
import { ACTIONS, actionsFor, hotSensors, phaseOf, stillTooHot, type Action, type MachinePhase, type MachineView } from './actions';

const IDLE: MachineView = { connected: true, job: null, homing: false, probing: false, configuring: false, resuming: false, uploading: false, faults: [], hot: [], interrupted: false };
const job = (state: JobProgress['state'], more: Partial<JobProgress> = {}): JobProgress => ({ state, stop: 3, stops: 10, ...more });
const E30 = { code: 30, message: 'printhead not responding', atMs: 0 };
const E31 = { code: 31, message: 'over-temperature T3 56.0 (soft limit)', atMs: 0 };

const VIEWS: Record<MachinePhase, MachineView> = {
  disconnected: { ...IDLE, connected: false },
  idle: IDLE,
  faulted: { ...IDLE, faults: [E30] },
  homing: { ...IDLE, homing: true },
  probing: { ...IDLE, probing: true },
  configuring: { ...IDLE, configuring: true },
  resuming: { ...IDLE, resuming: true, homing: true, interrupted: true },
  uploading: { ...IDLE, uploading: true },
  running: { ...IDLE, job: job('running') },
  cooling: { ...IDLE, job: job('running', { paced: true, cooling: true }) },
  paused: { ...IDLE, job: job('paused') },
};

const MACHINE = ['expose', 'frame', 'home', 'move', 'release', 'selfTest', 'probe', 'mesh', 'settings', 'flash'] as const;
/** The actions open in each phase; every other one is closed and says why. */
const OPEN: Record<MachinePhase, readonly Action[]> = {
  disconnected: ['flash'], // no printer to interrupt: any board may be flashed
  idle: MACHINE,
  faulted: MACHINE.filter((a) => a !== 'probe' && a !== 'mesh'),
  homing: [],
  probing: [],
  configuring: [],
  resuming: [],
  uploading: [],
  running: ['pause', 'stop'],
  cooling: ['pause', 'stop'],
  paused: ['continue', 'continuePaced', 'stop'],
};

describe('actionsFor', () => {
  for (const [phase, view] of Object.entries(VIEWS) as [MachinePhase, MachineView][]) {
    it(`${phase}: opens ${OPEN[phase].join(', ') || 'nothing'}, and says why for the rest`, () => {
      expect(phaseOf(view)).toBe(phase);
      const actions = actionsFor(view);
      for (const a of ACTIONS) {
        const gate = actions[a];
        expect(gate.open, `${phase} ${a}`).toBe(OPEN[phase].includes(a));
        if (!gate.open) expect(gate.why, `${phase} ${a}`).toMatch(/\w{3,}/);
      }
    });
  }

  it('names the reason of the phase: a paused job, a homing, a resume, no link', () => {
    expect(actionsFor(VIEWS.paused).expose.why).toBe('a job is paused: continue or stop it first');
    expect(actionsFor(VIEWS.running).home.why).toBe('a job is running');
    expect(actionsFor(VIEWS.cooling).move.why).toContain('waiting for the head to cool');
    expect(actionsFor(VIEWS.homing).home.why).toBe('the machine is homing already');
    expect(actionsFor(VIEWS.resuming).expose.why).toContain('resuming');
    expect(actionsFor(VIEWS.disconnected).stop.why).toBe('not connected');
    expect(actionsFor(VIEWS.idle).continue.why).toBe('no job is paused');
    expect(actionsFor(VIEWS.running).continue.why).toBe('the job is running');
    expect(actionsFor(VIEWS.faulted).probe.why).toBe('the printhead does not answer (E30 printhead not responding)');
    expect(actionsFor(VIEWS.probing).mesh.why).toBe('the probe is at work (probing the bed takes a while)');
    expect(actionsFor(VIEWS.probing).expose.why).toBe('the probe is at work (probing the bed takes a while)');
    expect(actionsFor(VIEWS.running).settings.why).toBe('a job is running');
    expect(actionsFor(VIEWS.running).flash.why).toBe('a job is running: flashing restarts the board');
    expect(actionsFor(VIEWS.configuring).expose.why).toBe('settings are being written');
  });

  it('offers an interrupted job for resuming only to a machine that is free', () => {
    expect(actionsFor({ ...IDLE, interrupted: true }).resume.open).toBe(true);
    expect(actionsFor({ ...IDLE, interrupted: true }).discard.open).toBe(true);
    expect(actionsFor({ ...IDLE, interrupted: true, homing: true }).resume).toEqual({ open: false, why: 'the machine is homing' });
    expect(actionsFor(VIEWS.resuming).resume.open).toBe(false);
    expect(actionsFor(IDLE).resume.why).toBe('no interrupted job');
  });

  it('keeps a job paused to cool from continuing while a sensor is over its limit, and lets it go once cooled', () => {
    const hot = { ...VIEWS.paused, job: job('paused', { reason: 'overtemp' }), faults: [E31] };
    expect(actionsFor({ ...hot, hot: ['T3 56.0 °C (limit 55 °C)'] }).continue).toEqual({ open: false, why: 'T3 56.0 °C (limit 55 °C) is still too hot' });
    expect(actionsFor({ ...hot, hot: ['T3 56.0 °C (limit 55 °C)', 'T4 51.0 °C (limit 50 °C)'] }).continue.why).toMatch(/, T4 .* are still too hot$/);
    expect(actionsFor(hot).continue.open).toBe(true); // E31 stands until the job continues; the readings decide
    expect(actionsFor({ ...hot, faults: [E30] }).continue.why).toBe('the printhead is still faulted: E30 printhead not responding');
    expect(actionsFor({ ...hot, faults: [{ code: 33, message: 'printhead refused an exposure', atMs: 0 }] }).continue.open).toBe(true); // the Mega judges it
  });

  it('lets a job paused to cool continue paced while it is still hot: the Mega waits for the head to cool first', () => {
    const hot = { ...VIEWS.paused, job: job('paused', { reason: 'overtemp' }), faults: [E31], hot: ['T3 56.0 °C (limit 55 °C)', 'T4 51.0 °C (limit 50 °C)'] };
    expect(actionsFor(hot).continuePaced).toEqual({ open: true });
    expect(actionsFor(hot).continue.open).toBe(false);
    expect(actionsFor({ ...hot, faults: [E31, E30] }).continuePaced).toEqual({ open: false, why: 'the printhead is still faulted: E30 printhead not responding' });
    expect(actionsFor({ ...hot, job: job('running', { paced: true, cooling: true }) }).continuePaced.why).toBe('the job is running');
    expect(actionsFor({ ...IDLE, hot: hot.hot }).continuePaced.why).toBe('no job is paused');
  });

  it('counts a running job before a homing, and a job that ended as none', () => {
    expect(phaseOf({ ...IDLE, job: job('running'), homing: true })).toBe('running');
    for (const s of ['done', 'aborted', 'failed', 'ready', 'idle'] as const) expect(phaseOf({ ...IDLE, job: job(s) })).toBe('idle');
  });
});

describe('hotSensors and stillTooHot', () => {
  it('lists the sensors at or over their limit, and agrees in number', () => {
    expect(hotSensors([550, 400, 300, 300, 300, 300], [55, 55, 55, 55, 50, 50])).toEqual(['T0 55.0 °C (limit 55 °C)']);
    expect(hotSensors(null, [55])).toEqual([]);
    expect(stillTooHot(['T0 55.0 °C (limit 55 °C)'])).toBe('T0 55.0 °C (limit 55 °C) is still too hot');
    expect(stillTooHot(['T0 a', 'T1 b'])).toBe('T0 a, T1 b are still too hot');
  });
});
