// What the page asks the work worker (worker.ts) and what it answers: plain data that survives
// structured cloning, one request kind per piece of heavy work.

import type { FileProblems } from '../pcb/problem-words';
import type { LayerKind } from '../pcb/layer-kind';
import type { KindSource } from '../pcb/layer-content';
import type { Mesh } from '../planner/mesh';
import type { MotionModel } from '../planner/time-model';
import type { JobFormat, PrintJob, StrategyName } from '../protocol/job-types';
import type { Finding } from '../studio/dry-run';
import type { MachineCheck } from '../job/machine-finding';
import type { UploadSize } from '../job/upload-time';
import type { MachineConfig } from '../studio/machine-config';
import type { Cut } from '../studio/objects/clipping';
import type { DoseBatch } from '../job/dose-batch';
import type { TwoSided } from '../studio/objects/board-object';
import type { ArtworkObject } from '../studio/objects/objects';
import type { Polarity } from '../studio/objects/raster';

/** How far the work has got: a stage in words, and where it counts, how many of how many. */
export interface Progress {
  stage: string;
  done?: number;
  of?: number;
}

export type WorkRequest =
  /**
   * The preview's plan; the worker keeps it for `preview-grid`. `auto`: in its fastest order, of
   * those whose scan strokes stay within the bed's width `bedXUm`.
   */
  | { kind: 'plan'; job: PrintJob; machine: MotionModel; auto?: boolean; bedXUm?: number }
  /** The kept plan's light up to stop (or pass) `upTo`, in bins of at most `maxSide` a side. */
  | { kind: 'preview-grid'; upTo: number; maxSide: number }
  /** A job that ran, in its order: what each of its dose records should give, and to which cells (job/dose-plan.ts), kept for `dose-map`. */
  | { kind: 'dose-plan'; job: PrintJob; machine: MotionModel }
  /** The page's dose ledger's changes since the last batch: the kept job's delivered-dose map, counted and binned in at most `maxSide` pixels a side. */
  | { kind: 'dose-map'; batch: DoseBatch; maxSide: number }
  /**
   * The check before an exposure (studio/dry-run.ts); `auto`: in its fastest order, of those that
   * stay on the config's bed. `boards`: the drawing's two-sided boards, one side a job.
   */
  | { kind: 'dry-run'; job: PrintJob; config: MachineConfig; auto: boolean; jobFormat?: JobFormat; linkBaud?: number; opts: { mesh?: Mesh | null; leveling?: boolean | null; startC?: number[] | null; cuts?: Cut[]; boards?: TwoSided[]; machine?: MachineCheck } }
  /** A picture embedded as a data: URL, decoded and kept. */
  | { kind: 'read-picture'; src: string }
  /** A board's files, as picked or embedded as a data: URL (pcb/board-artwork.ts), read and kept. */
  | { kind: 'read-board'; src?: string; files?: { name: string; text: string }[] }
  /** An artwork object's doses on its box: drawn, turned, mirrored and in the job's polarity. */
  | { kind: 'raster'; object: ArtworkObject; polarity: Polarity };

export type WorkReply = { id: number; progress: Progress } | { id: number; result: unknown } | { id: number; error: string; problems?: FileProblems[] };

export interface PictureRead {
  pixels: { width: number; height: number };
  lineArt: boolean;
}

export interface BoardRead {
  /** The files embedded as one data: URL, the object's `src`. */
  src: string;
  /** The board's window in µm, what its box shows. */
  pixels: { width: number; height: number };
  /** Each file's kind as guessed, in the files' order; a file with nothing read is 'other', 'unread'. */
  kinds: { file: string; kind: LayerKind; from: KindSource | 'unread' }[];
  problems: FileProblems[];
  /** Files that draw nothing, as is normal for their kind (an empty paste layer, an NPTH.drl with no holes). */
  notes: FileProblems[];
}

export interface DryRunSummary {
  order: StrategyName;
  findings: Finding[];
  duty: number[];
  estimateUs: number;
  /** The paced forecast's time when pacing avoids every pause, else null. */
  pacedUs: number | null;
  /** The job's bytes as the printer's job format writes them, and on the wire. */
  upload: UploadSize;
}
