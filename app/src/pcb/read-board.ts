// Reads a board's Gerber and Excellon files into one set of layers, each with a guessed kind, and says plainly what went wrong.
import { isEmptyBox, type BoxMm, type Paint } from './artwork';
import { drawingMix, guessKinds, looksLikeCopper, type KindGuess, type KindSource } from './layer-content';
import { isCopper, type LayerKind } from './layer-kind';
import { ARC_MISMATCH_MM, HAIRLINE_MM, plotToArtwork, type Hole, type Slot } from './plot-to-artwork';
import { fileType, plotFile, zeroSetOffset, type LibraryWarning, type PlotObject, type Units } from './tracespace';

export interface BoardLayer {
  file: string;
  /** Guessed from the file's attributes, name or comments (an Excellon file is always 'drill'); the user may change it. */
  kind: LayerKind;
  /** How the kind was found: 'content' when no file said it was copper and this one draws as copper does. */
  kindFrom: KindSource;
  format: 'gerber' | 'excellon';
  /** The units the file is written in; everything here is in millimetres whatever they are. */
  units: Units;
  /** What the layer draws, in board millimetres, Y up as in the file. */
  boundsMm: BoxMm;
  /** The same with draws taken by their centre lines (an outline's board edge); as boundsMm when not given. */
  lineBoundsMm?: BoxMm;
  /** The artwork in drawing order. */
  paints: Paint[];
  /** Flash centres of a drill file: the holes. Empty for other files. */
  holes: Hole[];
  /** A drill file's slots (G85, routed paths), each a straight run of its tool. Empty for other files. */
  slots: Slot[];
  /** The library's remarks that change nothing drawn (deprecated commands, assumed formats), with line numbers. */
  notes: string[];
}

export interface BoardProblem {
  file: string;
  message: string;
}

export interface BoardSet {
  layers: BoardLayer[];
  problems: BoardProblem[];
  /** Files that draw nothing, as is normal for their kind (KiCad writes an empty paste layer or NPTH.drl): said quietly, not as problems. */
  notes: BoardProblem[];
}

export interface BoardFile {
  name: string;
  text: string;
}

// Library warnings that mean something in the file was not drawn or was drawn differently from what it says.
// Selecting tool 0 is how drill files put the tool away (KiCad ends with T0): not a loss.
const DRAWING_LOST = /not defined|unknown tool|impossible arc|not strokable|cannot draw arc|unrecognized primitive|cannot change tool|flash in region/;
const TOOL_PUT_AWAY = /^tool 0+ is not defined$/;
// Gerber X2 attributes (%TF, %TA, %TO, %TD) describe, they do not draw: the library skips them, and so do the notes.
const ATTRIBUTE = /^block "%T[FAOD]\b/;

// Image and aperture transformations the library does not apply (it skips the command); each changes the picture.
const NOT_APPLIED: [RegExp, string][] = [
  [/%IPNEG\*%/, 'a negative image (%IPNEG) is not supported: the layer is drawn positive'],
  [/%MI(?:A1|B1|A1B1)\*%/, 'image mirroring (%MI) is not applied'],
  [/%SF(?!A1(?:\.0*)?B1(?:\.0*)?\*%)[^%]*%/, 'image scaling (%SF) is not applied'],
  [/%OF(?!A0(?:\.0*)?B0(?:\.0*)?\*%)[^%]*%/, 'image offset (%OF) is not applied'],
  [/%IR(?:90|180|270)\*%/, 'image rotation (%IR) is not applied'],
  [/%L[MRS](?!N\*|0(?:\.0*)?\*|1(?:\.0*)?\*)[^%]*%/, 'aperture mirroring, rotation or scaling (%LM, %LR, %LS) is not applied'],
  [/%FS[LTD]?I|^G91\*/m, 'incremental coordinates are not supported: the layer is drawn as if absolute'],
];

/** Reads every file; a file that cannot be used is left out with a problem saying why. Never throws. */
export function readBoard(files: readonly BoardFile[]): BoardSet {
  const kinds = guessKinds(files);
  const read: Read[] = [];
  const problems: BoardProblem[] = [];
  const notes: BoardProblem[] = [];
  files.forEach((f, i) => {
    const said = (message: string) => problems.push({ file: f.name, message });
    const noted = (message: string) => notes.push({ file: f.name, message });
    const layer = readLayer(f, kinds[i], said, noted);
    if (layer) read.push(layer);
  });
  if (!read.some((r) => isCopper(r.layer.kind))) problems.push(...takeCopper(read));
  return { layers: read.map((r) => r.layer), problems, notes };
}

interface Read {
  layer: BoardLayer;
  copperLike: boolean;
  /** Where the file flashes its apertures, mm: its pads. */
  flashes: Float64Array;
}

/**
 * No file says it is copper: of those that draw as copper does, the one with the most pads where no hole is
 * drilled is taken for the top copper (surface-mount parts sit on top), and with exactly two, the other for
 * the bottom. Where the board has holes, only files that flash a pad on at least half of them are copper: a
 * legend's or a mask's few flashes (fiducials, logos) are not pads, though they lie where no hole is. Named
 * files sort "bottom" before "top" as often as not, so the order says nothing. The choice and its reason are
 * said, as the person must check it.
 */
function takeCopper(read: Read[]): BoardProblem[] {
  const copperLike = read.filter((r) => r.copperLike && r.layer.kindFrom === 'none');
  if (copperLike.length === 0) return [];
  const holes = holeKeys(read.flatMap((r) => r.layer.holes));
  const padsOnHoles = (r: Read) => r.flashes.length / 2 - padsWithoutHole(r.flashes, holes);
  const padded = holes.size >= MIN_HOLES_TO_TELL ? copperLike.filter((r) => padsOnHoles(r) >= holes.size / 2) : [];
  const candidates = padded.length > 0 ? padded : copperLike;
  const surface = candidates.map((c) => padsWithoutHole(c.flashes, holes));
  const most = Math.max(...surface);
  const top = surface.indexOf(most);
  Object.assign(candidates[top].layer, { kind: 'copper-top', kindFrom: 'content' });
  const file = candidates[top].layer.file;
  if (candidates.length === 1) return [];
  if (candidates.length === 2) Object.assign(candidates[1 - top].layer, { kind: 'copper-bottom', kindFrom: 'content' });
  const others = candidates.filter((_, i) => i !== top).map((c, i) => `${c.layer.file} ${surface[i >= top ? i + 1 : i]}`);
  const clear = surface.filter((n) => n === most).length === 1;
  return [
    {
      file,
      message: clear
        ? `taken for the top copper from what it draws: ${most} pads without a hole, where surface-mount parts sit (against ${others.join(', ')}); check it`
        : `taken for the top copper only because it comes first: ${candidates.length} files draw as copper does and nothing tells their sides apart (pads without a hole: ${most} each); check which is the top`,
    },
  ];
}

/** Below this many holes, pads on holes tell copper from a legend no better than chance. */
const MIN_HOLES_TO_TELL = 10;

/** Holes by their place to the nearest 0.05 mm. */
const holeKey = (x: number, y: number) => `${Math.round(x * 20)},${Math.round(y * 20)}`;

function holeKeys(holes: readonly Hole[]): Set<string> {
  return new Set(holes.map((h) => holeKey(h.x, h.y)));
}

function padsWithoutHole(flashes: Float64Array, holes: Set<string>): number {
  let n = 0;
  for (let i = 0; i < flashes.length; i += 2) {
    const [kx, ky] = [Math.round(flashes[i] * 20), Math.round(flashes[i + 1] * 20)];
    let drilled = false;
    for (let dx = -1; dx <= 1 && !drilled; dx++) for (let dy = -1; dy <= 1 && !drilled; dy++) drilled = holes.has(`${kx + dx},${ky + dy}`);
    if (!drilled) n++;
  }
  return n;
}

function readLayer(f: BoardFile, guess: KindGuess, problem: (message: string) => void, note: (message: string) => void): Read | null {
  if (f.text.trim() === '') return problem('the file is empty'), null;
  if (/[\0-\x08\x0e-\x1f]/.test(f.text.slice(0, 4096))) return problem('not a Gerber or Excellon drill file: it is not text'), null;
  const type = fileType(f.text);
  if (!type) return problem('not a Gerber or Excellon drill file: it has no Gerber format or aperture commands, no drill header and no drill coordinates'), null;
  try {
    const plot = plotFile(f.text, type);
    const arcSlackMm = arcSlack(f.text, plot.units);
    const art = plotToArtwork(plot, arcSlackMm);
    const format = plot.filetype === 'drill' ? 'excellon' : 'gerber';
    const lost: string[] = [];
    for (const tool of art.unknownTools) lost.push(`tool ${tool} is flashed but never defined: those flashes are left out`);
    for (const tool of art.shapelessTools) lost.push(`aperture ${tool} has no shape (its macro is not defined or draws nothing): its flashes are left out`);
    if (art.malformed) lost.push(`${art.malformed} shape${art.malformed > 1 ? 's' : ''} with a size or place that is not a number left out`);
    if (art.paints.length === 0 || isEmptyBox(art.boundsMm)) {
      for (const message of lost) problem(message);
      const empty = format === 'excellon' ? 'the drill file has no holes' : 'the Gerber file draws nothing';
      return (lost.length === 0 && emptyIsNormal(format === 'excellon' ? 'drill' : guess.kind) ? note : problem)(empty), null;
    }
    const notes: string[] = [];
    if (art.hairlines) {
      // An outline drawn so is usual (Eagle): a note. Elsewhere the width drawn is the studio's, so it is said.
      const said = `${art.hairlines} draw${art.hairlines > 1 ? 's' : ''} with a zero-width aperture, drawn ${HAIRLINE_MM} mm wide`;
      if (guess.kind === 'outline') notes.push(said);
      else lost.push(said);
    }
    if (art.impossibleArcs) lost.push(`${art.impossibleArcs} impossible arc${art.impossibleArcs > 1 ? 's' : ''}, whose end lies more than ${+arcSlackMm.toFixed(3)} mm nearer to or further from the centre than the start: drawn as written, with a jump at the end`);
    for (const w of plot.warnings) {
      if (DRAWING_LOST.test(w.message) && !TOOL_PUT_AWAY.test(w.message)) problem(lineOf(w));
      else if (!ATTRIBUTE.test(w.message)) notes.push(lineOf(w));
    }
    for (const message of lost) problem(message);
    if (format === 'gerber') for (const [pattern, message] of NOT_APPLIED) if (pattern.test(f.text)) problem(message);
    if (format === 'excellon' && zeroSetOffset(f.text)) problem('a zero set (G93) that moves the origin is not applied: the holes are drawn from the file’s own origin');
    const layer: BoardLayer = {
      file: f.name,
      kind: format === 'excellon' ? 'drill' : guess.kind,
      kindFrom: format === 'excellon' ? 'content' : guess.from,
      format,
      units: plot.units,
      boundsMm: art.boundsMm,
      lineBoundsMm: art.lineBoundsMm,
      paints: art.paints,
      holes: art.holes,
      slots: art.slots,
      notes,
    };
    const flashes = format === 'gerber' ? flashPlaces(plot.objects, plot.units === 'in' ? 25.4 : 1) : new Float64Array(0);
    return { layer, copperLike: format === 'gerber' && looksLikeCopper(drawingMix(plot.objects)), flashes };
  } catch (e) {
    return problem(`could not be read: ${e instanceof Error ? e.message : String(e)}`), null;
  }
}

/**
 * A CAD tool writes every layer it is asked for, drawn or not: a board with no parts underneath has an
 * empty bottom paste, silk or mask, one with no unplated holes an empty NPTH drill file. A copper layer,
 * an outline or a file of no known kind that draws nothing is a real problem.
 */
const emptyIsNormal = (kind: LayerKind): boolean => kind === 'drill' || /^(paste|silk|mask)-/.test(kind);

/** How far an arc's end may stray from its circle: ARC_MISMATCH_MM, or three steps of the file's coordinates (%FSLAX23: 0.001 in). */
function arcSlack(text: string, units: Units): number {
  const decimals = /%FS[LTD]?[AI]?X\d(\d)/.exec(text);
  const step = decimals ? 10 ** -Number(decimals[1]) * (units === 'in' ? 25.4 : 1) : 0;
  return Math.max(ARC_MISMATCH_MM, 3 * step);
}

function flashPlaces(objects: readonly PlotObject[], k: number): Float64Array {
  const out: number[] = [];
  for (const o of objects) if (o.type === 'pad') out.push(o.x * k, o.y * k);
  return Float64Array.from(out);
}

/** The library counts lines from 0. */
const lineOf = (w: LibraryWarning) => `line ${w.line + 1}: ${w.message}`;
