// The Mega's settings as the app uses them (M850 / M500-M503, CONFIG.TXT on SD): their defaults, and
// the motion they give the planner's time model.

import type { MotionModel } from '../planner/time-model';
import { NANO_LINK_BAUDS } from '../protocol/nano';
import { SETTING_DEFAULTS } from './settings-defaults';

/** Each key's value after M502, in the text form M850 takes. */
export const CONFIG_DEFAULTS: Readonly<Record<string, string>> = SETTING_DEFAULTS;

/** A key's value as a number; the defaults make every key parse. */
export function num(config: Record<string, string>, key: string): number {
  return Number(config[key] ?? CONFIG_DEFAULTS[key]);
}

/** The Mega's step engine steps an axis no faster than this (`kMaxStepRate`, firmware/mega/src/step_profile.h). */
export const MAX_STEP_RATE = 16000;

/**
 * An axis's top speed in µm/s: its setting (`speed.travel`, or `speed.z`), or what the step engine
 * runs at the axis's steps/mm if that is less, as the Mega holds every move to it.
 */
export function topSpeedUmS(config: Record<string, string>, axis: number): number {
  const setting = Math.round(num(config, axis === 2 ? 'speed.z' : 'speed.travel') * 1000);
  const stepsMilli = Math.round(num(config, ['steps_per_mm.x', 'steps_per_mm.y', 'steps_per_mm.z'][axis]) * 1000);
  return Math.min(setting, Math.floor((MAX_STEP_RATE * 1_000_000) / stepsMilli));
}

/**
 * The printhead link's speed this firmware's Mega plans and runs a job at when its Nano takes the
 * raise (kJobLinkBaud in firmware/mega/src/printhead_link.h: it raises the link to 250000 once the
 * Nano is known); the estimates' speed when the printer does not say (`Cap:LINK_BAUD`, mega.md M115).
 */
export const BOARD_LINK_BAUD = 250000;

/**
 * The link speed to price a job at: what the printer said in `M115` (`Cap:LINK_BAUD`: 115200 once its
 * Nano failed a raise, protocol/nano.md "Link speed"), when it is a speed the link can take; else
 * BOARD_LINK_BAUD.
 */
export function linkBaudOf(reported: number | null | undefined): number {
  return reported != null && NANO_LINK_BAUDS.includes(reported) ? reported : BOARD_LINK_BAUD;
}

/** The motion the planner's time model prices (protocol/planner.md), from the settings, starting at `startUm`. */
export function motionOf(config: Record<string, string>, startUm: [number, number] = [0, 0], linkBaud = BOARD_LINK_BAUD): MotionModel {
  return {
    vmaxUmS: [topSpeedUmS(config, 0), topSpeedUmS(config, 1)],
    accelUmS2: [num(config, 'accel.x') * 1000, num(config, 'accel.y') * 1000],
    settleUs: num(config, 'settle_ms') * 1000,
    overheadUs: num(config, 'stop_overhead_us'),
    startUm,
    stepsMilli: [Math.round(num(config, 'steps_per_mm.x') * 1000), Math.round(num(config, 'steps_per_mm.y') * 1000)],
    linkBaud,
  };
}
