// The machine's motion as the planner reads it (protocol/planner.md "Time model"): the C++ time model
// prices it (planner-wasm.ts moveTimeUs, engineMoveUs, stopCostUs); here only what the app words with it.

export interface MotionModel {
  vmaxUmS: [number, number];
  accelUmS2: [number, number];
  settleUs: number;
  overheadUs: number;
  startUm: [number, number];
  /** X and Y steps per mm × 1000: the step engine moves in whole steps. */
  stepsMilli: [number, number];
  /**
   * The printhead link's speed the job runs at, one of the Nano's `L` speeds (nano.md "Link speed"):
   * it times each stop's F line, a pass's G lead and its programs on the wire (planner.md).
   */
  linkBaud: number;
}

/**
 * The Mega's step engine (firmware/mega/src/step_profile.h): a 2 MHz step timer, at most 16000 steps/s,
 * for wording why it cannot run a scan's window (planner-wasm.ts engineRefusal).
 */
export const ENGINE_TICK_HZ = 2_000_000;
export const ENGINE_MAX_RATE = 16000;
