// The preview's colours: dose from dark to UV violet to white-hot, one colour per LED, and mesh Z.

export const LED_COLOURS: [number, number, number][] = [[123, 47, 247], [194, 24, 91], [21, 101, 192], [0, 137, 123]];

/** 0 → the bed's near-white; up to 1 → deep violet; the share of the job's longest exposure. */
export function doseColour(share: number): [number, number, number] {
  const t = Math.max(0, Math.min(1, share));
  return [Math.round(250 - t * (250 - 60)), Math.round(250 - t * (250 - 10)), Math.round(250 - t * (250 - 140))];
}
