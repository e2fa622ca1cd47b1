// The printer's own clock as the app follows it: wall time scaled by how fast the printer runs
// (1 for a real machine, N for the simulated printer at ?simSpeed=N). Rates the app derives from
// reports (°C a minute) are per the printer's second, not the browser's.

export class DeviceClock {
  #deviceS = 0;
  #lastWallMs: number | null = null;

  constructor(private readonly wallMs: () => number = () => performance.now()) {}

  /**
   * The printer's seconds now, advanced from the last reading at `scale` printer seconds per wall
   * second: it never goes back, even when the link changes from a fast simulated printer to a real one.
   */
  nowS(scale: number): number {
    const wall = this.wallMs();
    if (this.#lastWallMs !== null) this.#deviceS += (Math.max(0, wall - this.#lastWallMs) / 1000) * scale;
    this.#lastWallMs = wall;
    return this.#deviceS;
  }
}
