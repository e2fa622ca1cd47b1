// Test support: the real boards in corpus/, each with the truth written down beside it (truth.json), and gerbv's judgement of them (Node only).
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { agreement, gerbvCells, gerbvDrill, matchHoles, onEdge, type Agreement, type HoleMatch } from './gerbv-reference';
import type { LayerKind } from './layer-kind';
import type { Hole, Slot } from './plot-to-artwork';
import { rasteriseBoard } from './rasterise';
import type { BoardFile, BoardLayer, BoardSet } from './read-board';

export const CORPUS = join(import.meta.dirname, 'corpus');

/** What truth.json says of a board: written down from the files' headers, the tool's naming, and gerbv. */
export interface BoardTruth {
  /** The CAD tool's family, for counting how many the corpus covers. */
  cad: string;
  /** The tool and version that wrote the files. */
  tool: string;
  /** Every file's own header says what it is (Gerber X2 file functions, EasyEDA's "G04 Layer:"), drill files aside. */
  kindsInHeaders: boolean;
  /** Each file that draws something, and its true kind. */
  kinds: Record<string, LayerKind>;
  /** Files that draw nothing (an empty silk or paste layer), and what they would have been. */
  empty: Record<string, LayerKind>;
  /** Files the studio must say something of (a part of them it draws differently from the file), and a phrase its words hold. */
  said: Record<string, string>;
  /**
   * The outline file, its size as gerbv draws it (stroke included), and the width of the line it is drawn
   * with (from the file's aperture list). The board is cut along the line's centre: its size is the drawn
   * size less one line width.
   */
  outline: { file: string; widthMm: number; heightMm: number; lineWidthMm: number };
  /**
   * The drill files' holes: how many, how many of each diameter (mm, to 0.001 in), as gerbv reads them or, where
   * gerbv misreads some (`gerbvMisreads` of them, off every pad), as the tool's own listing says.
   */
  holes: { count: number; diametersMm: Record<string, number>; gerbvMisreads?: number; listing?: string };
  /** The drill files' slots (Excellon G85: a hole drawn from one end to the other), how many, and of each diameter. */
  slots?: { count: number; diametersMm: Record<string, number> };
  /** The defects of issue 40 this board shows (1 to 7). */
  defects: string[];
}

export interface CorpusBoard {
  name: string;
  truth: BoardTruth;
  files: BoardFile[];
  /** Where gerbv can read each file. */
  path(file: string): string;
}

const NOT_A_LAYER = /^(LICENSE|SOURCE\.md|truth\.json)$/;

export function corpusBoards(): CorpusBoard[] {
  return readdirSync(CORPUS, { withFileTypes: true })
    .filter((d) => d.isDirectory())
    .map((d) => {
      const dir = join(CORPUS, d.name);
      const truth = JSON.parse(readFileSync(join(dir, 'truth.json'), 'utf8')) as BoardTruth;
      const files = readdirSync(dir)
        .filter((f) => !NOT_A_LAYER.test(f))
        .sort()
        .map((name) => ({ name, text: readFileSync(join(dir, name), 'latin1') }));
      return { name: d.name, truth, files, path: (file: string) => join(dir, file) };
    })
    .sort((a, b) => a.name.localeCompare(b.name));
}

/** The file truth.json calls top (or bottom) copper. */
export function copperFile(truth: BoardTruth, side: 'top' | 'bottom'): string | undefined {
  return Object.keys(truth.kinds).find((f) => truth.kinds[f] === `copper-${side}`);
}

/** The same files under names that say nothing (f01.gbr, f02.gbr…, in the order of their real names). */
export function namesSayingNothing(files: readonly BoardFile[]): { files: BoardFile[]; realName: Map<string, string> } {
  const realName = new Map<string, string>();
  const renamed = files.map((f, i) => {
    const name = `f${String(i + 1).padStart(2, '0')}.gbr`;
    realName.set(name, f.name);
    return { name, text: f.text };
  });
  return { files: renamed, realName };
}

/**
 * Our cells of one layer against gerbv's, on a 0.1 mm grid half a millimetre around the layer's artwork.
 * `acrossOurEdge`: cells that differ away from gerbv's edges although an edge of the artwork crosses them (our
 * coverage is partial): a notch or gap narrower than a cell that gerbv, lighting whole pixels, fills or drops.
 * `unexplained`: cells that differ with no edge near, gerbv's or the artwork's.
 * `shifted`: whether gerbv's picture taken a quarter cell over judged (see GERBV_STROKE_BIAS).
 */
export function copperAgainstGerbv(
  set: BoardSet,
  layer: BoardLayer,
  path: string,
  pitchUm: number,
  floor: number,
): Agreement & { cols: number; rows: number; acrossOurEdge: number; unexplained: number; shifted: boolean } {
  const p = pitchUm / 1000;
  const x0 = Math.floor(layer.boundsMm.x0 * 10) / 10 - 0.5;
  const y0 = Math.floor(layer.boundsMm.y0 * 10) / 10 - 0.5;
  const cols = Math.ceil((layer.boundsMm.x1 + 0.5 - x0) / p);
  const rows = Math.ceil((layer.boundsMm.y1 + 0.5 - y0) / p);
  const ours = rasteriseBoard(set, { expose: [layer.file], pitchUm: { x: pitchUm, y: pitchUm }, threshold: 0.5, windowMm: { x0, y0, x1: x0 + cols * p, y1: y0 + rows * p } });
  const judge = (d: number) => {
    const theirs = gerbvCells(path, { cols, rows, x0: +(x0 + d * p).toFixed(4), y0: +(y0 - d * p).toFixed(4), pitchMm: p });
    let acrossOurEdge = 0;
    let unexplained = 0;
    for (const i of differingOffEdges(ours.cells, theirs, cols, rows)) {
      const c = ours.coverage[i];
      if (c > PARTIAL && c < 1 - PARTIAL) acrossOurEdge++;
      else unexplained++;
    }
    return { ...agreement(ours.cells, theirs, cols, rows), cols, rows, acrossOurEdge, unexplained, shifted: d !== 0 };
  };
  // gerbv's stroker, without antialiasing, lays thin strokes up to a quarter cell right of and below where
  // they are (gerbv-stroke-bias.test.ts shows it). Where gerbv's picture in place falls below the floor, or
  // differs away from every edge, its picture is also taken a quarter cell that way, and the closer of the two
  // judges. A quarter of 50 µm is far below what the machine can show.
  const inPlace = judge(0);
  if (inPlace.allAgree / inPlace.all >= floor && inPlace.unexplained === 0) return inPlace;
  const shifted = judge(GERBV_STROKE_BIAS);
  return shifted.allAgree > inPlace.allAgree ? shifted : inPlace;
}

/** How far, in cells, gerbv's non-antialiased stroker lays a thin stroke right of and below its place. */
export const GERBV_STROKE_BIAS = 0.25;

/** Coverage this far from 0 or 1 means an edge of the artwork crosses the cell, not rounding. */
const PARTIAL = 0.01;

/** Cells that differ whose 3 × 3 neighbourhood in gerbv's picture is all one value (as `agreement` counts them). */
function differingOffEdges(ours: Uint8Array, theirs: Uint8Array, cols: number, rows: number): number[] {
  const found: number[] = [];
  for (let r = 0; r < rows; r++) {
    for (let c = 0; c < cols; c++) {
      const i = r * cols + c;
      if (ours[i] !== theirs[i] && !onEdge(theirs, cols, rows, r, c)) found.push(i);
    }
  }
  return found;
}

/** gerbv's holes and slots of every drill file in the set, against ours; a slot matches one with both ends and its diameter alike. */
export function holesAgainstGerbv(
  set: BoardSet,
  path: (file: string) => string,
  toleranceMm: number,
  diameterToleranceMm: number,
): { ours: Hole[]; theirs: Hole[]; match: HoleMatch; slots: { ours: Slot[]; theirs: Slot[]; matched: number } } {
  const drills = set.layers.filter((l) => l.kind === 'drill');
  const ours = drills.flatMap((l) => l.holes);
  const gerbv = drills.map((l) => gerbvDrill(path(l.file)));
  const theirs = gerbv.flatMap((g) => g.holes);
  const slots = { ours: drills.flatMap((l) => l.slots), theirs: gerbv.flatMap((g) => g.slots), matched: 0 };
  const near = (ax: number, ay: number, bx: number, by: number) => Math.hypot(ax - bx, ay - by) <= toleranceMm;
  const alike = (a: Slot, b: Slot) =>
    Math.abs(a.diameterMm - b.diameterMm) <= diameterToleranceMm &&
    ((near(a.x0, a.y0, b.x0, b.y0) && near(a.x1, a.y1, b.x1, b.y1)) || (near(a.x0, a.y0, b.x1, b.y1) && near(a.x1, a.y1, b.x0, b.y0)));
  const unused = [...slots.ours];
  for (const t of slots.theirs) {
    const i = unused.findIndex((o) => alike(o, t));
    if (i >= 0) unused.splice(i, 1), slots.matched++;
  }
  return { ours, theirs, match: matchHoles(ours, theirs, toleranceMm, diameterToleranceMm), slots };
}

/** Whether a hole's centre lies on a flashed pad of a copper layer (not a track or a pour). */
export function onPad(copper: BoardLayer, h: Hole): boolean {
  return copper.paints.some((p) => !p.clear && p.shape.kind !== 'stadium' && p.shape.kind !== 'polygon' && p.box.x0 <= h.x && h.x <= p.box.x1 && p.box.y0 <= h.y && h.y <= p.box.y1);
}

/** How many holes have each of the given diameters (the nearest, within the tolerance); holes of none of them under 'other'. */
export function holesBySize(holes: readonly { diameterMm: number }[], diametersMm: readonly string[], toleranceMm: number): Record<string, number> {
  const counts: Record<string, number> = Object.fromEntries(diametersMm.map((d) => [d, 0]));
  for (const h of holes) {
    const off = (d: string) => Math.abs(Number(d) - h.diameterMm);
    const d = diametersMm.reduce((a, b) => (off(b) < off(a) ? b : a), diametersMm[0]);
    if (d !== undefined && off(d) <= toleranceMm) counts[d]++;
    else counts.other = (counts.other ?? 0) + 1;
  }
  return counts;
}

/**
 * Where the studio's default drill dots change the exposed copper: each changed cell with the hole (or slot) it
 * belongs to and how far its centre lies from that hole's centre (the slot's centre line), past the hole's edge
 * (mm; ≤ 0 inside the hole).
 */
export function dotsPastHoles(set: BoardSet, topCopper: string, pitchUm: number): { changed: number; worstPastEdgeMm: number; worstHoleMm: number } {
  const holes = set.layers.filter((l) => l.kind === 'drill').flatMap((l) => l.holes);
  const slots = set.layers.filter((l) => l.kind === 'drill').flatMap((l) => l.slots);
  const opts = { expose: [topCopper], pitchUm: { x: pitchUm, y: pitchUm }, threshold: 0.5 } as const;
  const bare = rasteriseBoard(set, { ...opts, drillClear: 'none' });
  const dotted = rasteriseBoard(set, { ...opts, drillClear: 'unexposed-dot', windowMm: bare.windowMm });
  const p = pitchUm / 1000;
  let changed = 0;
  let worstPastEdgeMm = -Infinity;
  let worstHoleMm = 0;
  for (let r = 0; r < bare.rows; r++) {
    for (let c = 0; c < bare.cols; c++) {
      const i = r * bare.cols + c;
      if (bare.cells[i] === dotted.cells[i]) continue;
      changed++;
      const x = bare.windowMm.x0 + (c + 0.5) * p;
      const y = bare.windowMm.y1 - (r + 0.5) * p;
      let best = Infinity;
      let hole = 0;
      for (const h of holes) {
        const past = Math.hypot(h.x - x, h.y - y) - h.diameterMm / 2;
        if (past < best) (best = past), (hole = h.diameterMm);
      }
      for (const s of slots) {
        const past = fromSegment(s, x, y) - s.diameterMm / 2;
        if (past < best) (best = past), (hole = s.diameterMm);
      }
      if (best > worstPastEdgeMm) (worstPastEdgeMm = best), (worstHoleMm = hole);
    }
  }
  return { changed, worstPastEdgeMm, worstHoleMm };
}

/** How far a point lies from a slot's centre line, end to end. */
function fromSegment(s: Slot, x: number, y: number): number {
  const dx = s.x1 - s.x0;
  const dy = s.y1 - s.y0;
  const len2 = dx * dx + dy * dy;
  const t = len2 > 0 ? Math.max(0, Math.min(1, ((x - s.x0) * dx + (y - s.y0) * dy) / len2)) : 0;
  return Math.hypot(s.x0 + t * dx - x, s.y0 + t * dy - y);
}
