// The printhead's thermal model: how its six sensors warm while LEDs are lit and cool towards the
// room. One model, with its constants here only, run by the simulated printhead (nano-model.ts)
// and by the dry run's forecast (studio/thermal-forecast.ts), so that what the app predicts is what
// the simulated printer then does. A real head differs: watch its thermal dashboard.

export const SENSORS = 6;
/** The sensor on the LEDs' constant-current drivers; every lit LED warms it a little. */
export const DRIVER_SENSOR = 4;

export interface HeadThermalModel {
  /** Where each sensor rests, °C. */
  ambientC: number[];
  /** °C per second a lit LED adds to its own sensor (T0-T3). */
  heatingCPerS: number;
  /** Newton cooling: the share of the gap to ambient a sensor loses per second. */
  coolingPerS: number;
  /** The share of each lit LED's heating that reaches the driver sensor. */
  driverShare: number;
  /** Heating on every LED sensor whether lit or not, °C/s: a fault tests force (over-temperature). */
  extraHeatingCPerS: number;
}

export const HEAD_THERMAL: HeadThermalModel = {
  ambientC: [23.1, 23.4, 22.9, 23.6, 22.4, 22.6],
  heatingCPerS: 2.5,
  coolingPerS: 0.08,
  driverShare: 0.3,
  extraHeatingCPerS: 0,
};

/** Each mask of lit LEDs as the LEDs' shares of the time: 0 or 1. */
const DUTY = Array.from({ length: 16 }, (_, lit) => [0, 1, 2, 3].map((led) => (lit >> led) & 1));

/** The six sensors' temperatures, °C, advanced through time with the LEDs' states. */
export class HeadThermal {
  readonly temp: number[];
  /** The hottest each sensor has been since start (or the last `resetPeak`). */
  readonly peak: number[];

  constructor(readonly model: HeadThermalModel = HEAD_THERMAL, startC: number[] = model.ambientC) {
    this.temp = startC.slice(0, SENSORS);
    this.peak = this.temp.slice();
  }

  /** °C/s sensor `i` gains from its heating with the LEDs of `lit` on (not counting cooling). */
  heating(i: number, lit: number): number {
    return this.heatingAt(i, DUTY[lit & 15]);
  }

  /** °C/s sensor `i` gains with each LED lit for its share `duty[led]` (0-1) of the time. */
  heatingAt(i: number, duty: readonly number[]): number {
    const m = this.model;
    if (i < 4) return m.heatingCPerS * duty[i] + m.extraHeatingCPerS;
    return i === DRIVER_SENSOR ? m.heatingCPerS * m.driverShare * (duty[0] + duty[1] + duty[2] + duty[3]) : 0;
  }

  /**
   * Holds the LEDs of `lit` on for `dtUs`. Exact for a constant input: each sensor approaches
   * ambient + heating ÷ cooling exponentially, so one long step equals many short ones, and the
   * peak within a step is at one of its ends.
   */
  advance(dtUs: number, lit: number): void {
    this.advanceDuty(dtUs, DUTY[lit & 15]);
  }

  /** Runs `dtUs` with each LED lit for its share `duty[led]` of it: the mean heating, exact as `advance` is for a steady input. */
  advanceDuty(dtUs: number, duty: readonly number[]): void {
    if (dtUs <= 0) return;
    const dt = dtUs / 1e6;
    const k = this.model.coolingPerS;
    const decay = Math.exp(-k * dt);
    for (let i = 0; i < SENSORS; i++) {
      const h = this.heatingAt(i, duty);
      const amb = this.model.ambientC[i];
      if (k > 0) {
        const settle = amb + h / k;
        this.temp[i] = settle + (this.temp[i] - settle) * decay;
      } else this.temp[i] += h * dt;
      if (this.temp[i] > this.peak[i]) this.peak[i] = this.temp[i];
    }
  }

  resetPeak(): void {
    for (let i = 0; i < SENSORS; i++) this.peak[i] = this.temp[i];
  }

  deciC(): number[] {
    return this.temp.map((t) => Math.round(t * 10));
  }
}
