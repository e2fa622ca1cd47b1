// The exposure job as the app, the ESP body (protocol/print-job.schema.json) and the planner see it.

/** `scan` exposes each pass on the move (protocol/planner.md "Scan mode"), `mixed` each pass on the move or stop by stop, whichever is cheaper ("Mixed mode"); the others stop and fire. */
export type StrategyName = 'raster' | 'serpentine' | 'shortest' | 'random' | 'scan' | 'mixed';

export const STRATEGY_NAMES: readonly StrategyName[] = ['raster', 'serpentine', 'shortest', 'random', 'scan', 'mixed'];

export type Dose =
  | { map: 'linear' | 'threshold'; level?: number; fullUs: number }
  | { map: 'linear' | 'threshold'; level?: number; targetUJcm2: number; irradianceUWcm2: number[] };

export interface PrintJob {
  name?: string;
  grid: { cols: number; rows: number };
  pitchUm: { x: number; y: number };
  originUm: { x: number; y: number };
  dose: Dose;
  leds: { offsets: [number, number][]; gainPermille?: number[] };
  thermal?: { coeffCentiPctPerC: number; refDeciC: number };
  strategy: { name: StrategyName; seed?: number };
  /** rows arrays of cols values 0-255, row 0 first. */
  gridData: ArrayLike<number>[];
}

/** Header of a job text, everything but the cells. */
export interface JobHeader {
  cols: number;
  rows: number;
  pitchUm: [number, number];
  originUm: [number, number];
  map: 'linear' | 'threshold';
  level: number;
  fullUs?: number;
  targetUJcm2?: number;
  irradianceUWcm2?: number[];
  gainPermille: number[];
  thermal: [number, number];
  offsets: [number, number][];
  strategy: StrategyName;
  seed: number;
}

export const JOB_LIMITS = {
  maxSide: 4096,
  maxCellsPerRecord: 32,
  maxGap: 4,
  /** Format 2: equal cells from this many on are a run token of an `rl` record (job.md "Run-length rows"). */
  minRun: 4,
  /** Format 2: the longest `rl` record, as long as the longest `r` record, so it fits a dialect line. */
  maxRecordBytes: 76,
} as const;

/** The job formats: 1 has `r` records only; 2 adds `rl`, run-length rows. */
export type JobFormat = 1 | 2;
