// The LEDs' thermal model that the dry run and the thermal dashboard share: apart from the dry run,
// so the dashboard, loaded first, does not bring the planner with it.

/**
 * How fast an LED's sensor warms with the LED lit and cools towards the room (°C/s, and the share
 * of the gap lost per second), and how much of that reaches the driver's sensor per LED. The
 * defaults are the simulated printer's; a real head should be measured (the thermal dashboard).
 */
export interface ThermalModel {
  heatingCPerS: number;
  coolingPerS: number;
  driverShare: number;
  ambientC: number;
}

export const DEFAULT_THERMAL: ThermalModel = { heatingCPerS: 2.5, coolingPerS: 0.08, driverShare: 0.3, ambientC: 23 };
