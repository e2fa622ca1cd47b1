// The machine as the studio sees it, from the Mega's settings (firmware/mega/CONFIG.md keys):
// the bed, the cell pitch, the motion the planner times, the LEDs and the thermal limits.

import { CONFIG_DEFAULTS, num } from '../machine/config';

export { motionOf } from '../machine/config';

export type MachineConfig = Record<string, string>;

export const DEFAULT_CONFIG: MachineConfig = CONFIG_DEFAULTS;

export function bedOf(c: MachineConfig) {
  return { bedMm: { x: num(c, 'bed.x'), y: num(c, 'bed.y') }, pitchUm: { x: num(c, 'pitch.x'), y: num(c, 'pitch.y') } };
}

/** Each sensor's soft limit, °C: T0-T3 the LEDs, T4 the driver, T5 the frame. */
export function limitsOf(c: MachineConfig): number[] {
  return [0, 1, 2, 3, 4, 5].map((i) => num(c, `thermal.limit.${i}`));
}

/** Where each LED sits on the head, in cells (`led.offset.k`), and its gain in ‰ (`led.gain.k`). */
export function ledsOf(c: MachineConfig): { offsets: [number, number][]; gainPermille: number[] } {
  const offsets = [0, 1, 2, 3].map((k) => (c[`led.offset.${k}`] ?? DEFAULT_CONFIG[`led.offset.${k}`]).split(',').map(Number) as [number, number]);
  return { offsets, gainPermille: [0, 1, 2, 3].map((k) => num(c, `led.gain.${k}`)) };
}
