// The simulated bed surface the probe finds: a tilt plus a few smooth bumps, in µm.

export interface BedShape {
  /** Z at the origin, µm. */
  z0: number;
  /** Tilt in µm per mm along X and Y. */
  tilt: [number, number];
  /** Gaussian bumps: centre (mm), radius (mm), height (µm). */
  bumps: { x: number; y: number; r: number; h: number }[];
}

export const DEFAULT_BED: BedShape = {
  z0: -1000, // the pin touches 1 mm below Z's switch (the probe reaches 3 mm below it, probe.h): homed, a deployed pin is clear
  tilt: [0.6, -0.4],
  bumps: [
    { x: 60, y: 140, r: 35, h: 45 },
    { x: 150, y: 50, r: 25, h: -30 },
  ],
};

/** Bed height at (x, y) in µm, for bed positions in µm. */
export function bedZ(shape: BedShape, xUm: number, yUm: number): number {
  const x = xUm / 1000, y = yUm / 1000;
  let z = shape.z0 + shape.tilt[0] * x + shape.tilt[1] * y;
  for (const b of shape.bumps) z += b.h * Math.exp(-((x - b.x) ** 2 + (y - b.y) ** 2) / (2 * b.r * b.r));
  return Math.round(z);
}
