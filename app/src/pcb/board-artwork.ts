// A board's files as one studio object's artwork: the files embedded in a data: URL, read once, and
// drawn over the board's window at any size in cells with the layers, drill dots and registration
// marks the object chooses (the studio loads this with import(), like all of app/src/pcb).
import { EMPTY_BOX, isEmptyBox, unionBox, type BoxMm, type Paint } from './artwork';
import type { LayerKind } from './layer-kind';
import { rasteriseBoard, boardBounds, type DrillClear } from './rasterise';
import { BoardUnreadable, problemsByFile } from './problem-words';
import { readBoard, type BoardFile, type BoardLayer, type BoardSet } from './read-board';

export const BOARD_SRC_PREFIX = 'data:application/vnd.uv-exposure.board+json;base64,';
/** A registration mark: a copper ring this wide, its bare centre this wide (a drill finds it). */
export const MARK_OUTER_MM = 2;
export const MARK_HOLE_MM = 0.6;
const MARKS_FILE = '\u0000registration marks';

/** What the object chooses; its fields of the same names (studio/objects/objects.ts BoardObject). */
export interface BoardLook {
  layers: readonly { kind: LayerKind; expose: boolean }[];
  drillClear: DrillClear;
  marks: readonly { x: number; y: number }[];
}

export function boardSrc(files: readonly BoardFile[]): string {
  const bytes = new TextEncoder().encode(JSON.stringify({ files: files.map((f) => ({ name: f.name, text: f.text })) }));
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return BOARD_SRC_PREFIX + btoa(binary);
}

export function boardFiles(src: string): BoardFile[] {
  if (!src.startsWith(BOARD_SRC_PREFIX)) throw new Error('this is not a board embedded by the studio');
  const binary = atob(src.slice(BOARD_SRC_PREFIX.length));
  const json = JSON.parse(new TextDecoder().decode(Uint8Array.from(binary, (c) => c.charCodeAt(0)))) as { files?: BoardFile[] };
  if (!Array.isArray(json.files) || !json.files.every((f) => typeof f?.name === 'string' && typeof f?.text === 'string')) throw new Error('the embedded board has no files');
  return json.files;
}

/** Each mark as a ring of copper with a bare centre, at mm from the window's lower left corner. */
export function markLayer(marks: BoardLook['marks'], window: BoxMm): BoardLayer {
  const R = MARK_OUTER_MM / 2, r = MARK_HOLE_MM / 2;
  const paints: Paint[] = marks.map((m) => {
    const cx = window.x0 + m.x, cy = window.y0 + m.y;
    const box = { x0: cx - R, y0: cy - R, x1: cx + R, y1: cy + R };
    return { shape: { kind: 'stack', parts: [{ shape: { kind: 'circle', cx, cy, r: R }, clear: false }, { shape: { kind: 'circle', cx, cy, r }, clear: true }] }, clear: false, box };
  });
  return { file: MARKS_FILE, kind: 'other', kindFrom: 'none', format: 'gerber', units: 'mm', boundsMm: paints.reduce((b, p) => unionBox(b, p.box), EMPTY_BOX), paints, holes: [], slots: [], notes: [] };
}

export interface BoardArtwork {
  set: BoardSet;
  /** The files' names in `src` order (a file with a problem has no layer). */
  files: string[];
  /** The board's window (boardWindow): what the object's box shows, at its true size. */
  windowMm: BoxMm;
  /** w × h cells over the window, row 0 at the top: 0 all covered … 255 bare. */
  cover(w: number, h: number, look: BoardLook): { width: number; height: number; values: Uint8Array };
}

/** How far copper may reach past an outline that still bounds the board (a pad's edge on the board's edge). */
const OUTLINE_SLACK_MM = 0.5;

const within = (inner: BoxMm, outer: BoxMm, slack: number) =>
  inner.x0 >= outer.x0 - slack && inner.y0 >= outer.y0 - slack && inner.x1 <= outer.x1 + slack && inner.y1 <= outer.y1 + slack;
const area = (b: BoxMm) => (b.x1 - b.x0) * (b.y1 - b.y0);

/**
 * The board's window: what the object spans, is clipped to and measures its marks from. The outline's when
 * there is one, taken by its centre line, where the board is cut (a KiCad Edge.Cuts line 0.1 mm wide around
 * 30 × 20 mm gives 30 × 20 mm; the outer half of the line lies outside); else what may be exposed (every layer but drawings, kind 'other', which are never exposed
 * and would stretch it: EasyEDA's drill drawing, DipTrace's dimensions). Of several outlines (an Eagle
 * dimension layer beside a milling layer, DipTrace's dimensions), the smallest that holds the copper.
 */
export function boardWindow(set: BoardSet): BoxMm {
  const layers = set.layers.filter((l) => !isEmptyBox(l.boundsMm));
  const boxOf = (ls: readonly BoardLayer[]) => ls.reduce((b, l) => unionBox(b, l.boundsMm), EMPTY_BOX);
  const exposable = layers.filter((l) => l.kind !== 'other' && l.kind !== 'outline');
  const copper = boxOf(exposable.filter((l) => l.kind === 'copper-top' || l.kind === 'copper-bottom'));
  const inside = isEmptyBox(copper) ? boxOf(exposable) : copper;
  const outlines = layers.filter((l) => l.kind === 'outline').map((l) => l.lineBoundsMm ?? l.boundsMm);
  const holding = isEmptyBox(inside) ? outlines : outlines.filter((o) => within(inside, o, OUTLINE_SLACK_MM));
  if (holding.length) return holding.reduce((a, b) => (area(b) < area(a) ? b : a));
  if (outlines.length) return outlines.reduce(unionBox);
  return isEmptyBox(inside) ? boardBounds(set) : inside;
}

/** Reads the embedded files; the last few looks are kept, so a change of tone or threshold does not draw the board again. */
export function boardArtwork(src: string): BoardArtwork {
  const files = boardFiles(src);
  const set = readBoard(files);
  const windowMm = boardWindow(set);
  if (isEmptyBox(windowMm)) throw new BoardUnreadable(problemsByFile([...set.problems, ...set.notes]));
  const kept = new Map<string, Uint8Array>();
  const names = files.map((f) => f.name);
  return {
    set,
    files: names,
    windowMm,
    cover(w, h, look) {
      const key = JSON.stringify([w, h, look.layers, look.drillClear, look.marks]);
      let values = kept.get(key);
      if (!values) {
        values = coverOf(set, names, windowMm, w, h, look);
        if (kept.size >= 4) kept.delete(kept.keys().next().value!);
        kept.set(key, values);
      }
      return { width: w, height: h, values };
    },
  };
}

function coverOf(set: BoardSet, names: string[], windowMm: BoxMm, w: number, h: number, look: BoardLook): Uint8Array {
  const kindOf = new Map(names.map((n, i) => [n, look.layers[i]]));
  const layers = set.layers.map((l) => ({ ...l, kind: kindOf.get(l.file)?.kind ?? l.kind }));
  const expose = set.layers.filter((l) => kindOf.get(l.file)?.expose).map((l) => l.file);
  if (look.marks.length) {
    layers.push(markLayer(look.marks, windowMm));
    expose.push(MARKS_FILE);
  }
  const pitchUm = { x: ((windowMm.x1 - windowMm.x0) * 1000) / w, y: ((windowMm.y1 - windowMm.y0) * 1000) / h };
  const r = rasteriseBoard({ layers, problems: set.problems, notes: set.notes }, { expose, pitchUm, windowMm, drillClear: look.drillClear });
  const values = new Uint8Array(w * h).fill(255);
  // Rounding may give a column or row more than asked: it lies past the window and is left out.
  for (let y = 0; y < Math.min(h, r.rows); y++)
    for (let x = 0; x < Math.min(w, r.cols); x++) values[y * w + x] = Math.round(255 * (1 - r.coverage[y * r.cols + x]));
  return values;
}
