// The one place that calls tracespace's gerber-parser and gerber-plotter (v4): a file's text in, the plotter's image objects out.
//
// Why v4 (gerber-parser 4.2.7, gerber-plotter 4.2.8, pinned exactly): it is tracespace's last stable line,
// the one pcb-stackup and gerber-to-svg are built on, and it handles every construct a board needs:
// apertures with holes, macros, regions, arcs in both quadrant modes, LPD/LPC, step and repeat, Excellon's
// formats. The v5 rewrite (@tracespace/parser 5.0.0-next.0, @tracespace/plotter 5.0.0-alpha.0) never left
// pre-release, and its plotter draws neither clear polarity nor step and repeat.
//
// Both are Node transform streams. Streaming would defer every object through process.nextTick, which a
// browser lacks, so the parser runs through its own parseSync and the plotter's transform is called
// directly, its push caught. Both still construct a stream, so the bundle carries the npm 'events' and
// 'buffer' packages (dependencies of ours for that reason).
import gerberParser from 'gerber-parser';
import { cutBlocks } from './block-apertures';
import gerberPlotter from 'gerber-plotter';
import { quarterArcCentre, type ArcCoord } from './single-quadrant';

export type Point = [number, number];
export type Units = 'mm' | 'in';

/** The primitives of an aperture, in its own coordinates; a 'layer' entry switches the following ones dark or clear. */
export type PadPrimitive =
  | { type: 'circle'; cx: number; cy: number; r: number }
  | { type: 'rect'; cx: number; cy: number; width: number; height: number; r: number }
  | { type: 'poly'; points: Point[] }
  | { type: 'ring'; cx: number; cy: number; r: number; width: number }
  | { type: 'clip'; shape: PadPrimitive[]; clip: PadPrimitive }
  | { type: 'layer'; polarity: 'dark' | 'clear' };

export type Segment =
  | { type: 'line'; start: Point; end: Point }
  | { type: 'arc'; start: [number, number, number]; end: [number, number, number]; center: Point; sweep: number; radius: number; dir: 'cw' | 'ccw' };

export type PlotObject =
  | { type: 'shape'; tool: string; shape: PadPrimitive[] }
  | { type: 'pad'; tool: string; x: number; y: number }
  | { type: 'fill'; path: Segment[] }
  | { type: 'stroke'; width: number; path: Segment[] }
  | { type: 'polarity'; polarity: 'dark' | 'clear' }
  | { type: 'repeat'; offsets: Point[] }
  | { type: 'size'; box: [number, number, number, number]; units: Units };

export interface LibraryWarning {
  line: number;
  message: string;
}

export interface Plot {
  filetype: 'gerber' | 'drill';
  /** The units of the plot's coordinates, as the file set them (or the library assumed: inches). */
  units: Units;
  objects: PlotObject[];
  /** How many commands the parser found: 0 means the text was not a Gerber or drill file at all. */
  commands: number;
  warnings: LibraryWarning[];
  /** Block apertures (%AB) by tool: each block plotted on its own, in the same units (block-apertures.ts). */
  blocks?: Map<string, Plot>;
}

interface ParserInternals {
  format: { filetype: 'gerber' | 'drill' | null };
  _syncResult: unknown[] | null;
  _process(text: string, filetype: 'gerber' | 'drill'): void;
  _flush(): void;
  on(event: 'warning', listener: (w: LibraryWarning) => void): unknown;
}

/**
 * Gerber or Excellon, from what the text says. The library's own guess (a '*' before the first line ends)
 * calls a Gerber file whose first line is a comment without one a drill file; its parseSync always guesses,
 * so the parse below is parseSync's three lines with the type given.
 */
export function fileType(text: string): 'gerber' | 'drill' | null {
  if (/%(?:FS|MO|AD|AM)|^[^;\n]*D0*[123]\*/m.test(text)) return 'gerber';
  if (/^\s*(?:M48|M71|M72|INCH|METRIC|;FILE_FORMAT|T\d+\s*[CF]|[XY][-+]?\d[\d.]*(?:[XY][-+]?\d[\d.]*)?\s*$)/m.test(text)) return 'drill';
  return null;
}

interface PlotterInternals {
  format: { units: Units | null };
  _pos: [number, number];
  _mode: 'i' | 'cw' | 'ccw' | null;
  _arc: 's' | 'm' | null;
  _lastOp: string | null;
  _epsilon: number | null;
  push: (o: PlotObject) => boolean;
  _transform(command: unknown, encoding: null, done: (error?: Error) => void): void;
  _flush(done: (error?: Error) => void): void;
  on(event: 'warning', listener: (w: LibraryWarning) => void): unknown;
}

/** A drawing command as the parser gives it (D01, D02, D03, or none: the last one again). */
interface OpCommand {
  type: 'op';
  op: string;
  coord: ArcCoord;
}
const isOp = (command: { type: string }): command is OpCommand => command.type === 'op';

/** A single-quadrant arc the plotter would skip for floating point alone, and the centre it should have. */
function quarterArcAt(plotter: PlotterInternals, command: OpCommand): [number, number] | null {
  const op = command.op === 'last' ? plotter._lastOp : command.op;
  const mode = plotter._mode;
  // No quadrant mode set: the plotter assumes single quadrant for an arc without a radius, and so does this.
  if (op !== 'int' || plotter._arc === 'm' || (mode !== 'cw' && mode !== 'ccw') || plotter._epsilon == null) return null;
  return quarterArcCentre(plotter._pos, command.coord, mode, plotter._epsilon);
}

/**
 * Old files put a mode code and a draw in one block ("G75G03I150J0X3550Y1701D01*"); the parser keeps the
 * first code and drops the rest of the block, draw included. Each such mode code gets a block of its own.
 */
export function splitModeCodes(text: string): string {
  return text.replace(/(^|\*)(\s*G0*(?:70|71|74|75|90|91))(?=\s*[GXYIJD])/gm, '$1$2*');
}

/**
 * Excellon's zero set, "G93X0Y0" (Veribest and Mentor write it before the first hole): the parser reads its
 * coordinates as a hole at the origin, drilled with whatever tool is current. It says where the origin is,
 * and drills nothing, so it leaves the text; an offset other than zero is reported by the caller (zeroSetOffset).
 */
export function dropZeroSet(text: string): string {
  return text.replace(/^[ \t]*G93(?!\d)[^\r\n]*/gm, '');
}

/** A zero set that moves the origin: not applied, so the holes would lie off the copper by that much. */
export const zeroSetOffset = (text: string): boolean => /^[ \t]*G93(?!\d)[^\r\n]*[XY][-+]?[0.]*[1-9]/m.test(text);

/** Parses and plots one file of the given type. May throw whatever the library throws; the caller makes that a problem. */
export function plotFile(text: string, filetype: 'gerber' | 'drill'): Plot {
  const cut = filetype === 'gerber' ? cutBlocks(text) : null;
  if (!cut) return plotText(text, filetype);
  const plot = plotText(cut.text, filetype);
  plot.blocks = new Map();
  for (const [tool, block] of cut.blocks) {
    const inner = plotFile(block.text, 'gerber');
    plot.blocks.set(tool, inner);
    for (const w of inner.warnings) plot.warnings.push({ line: block.line, message: `in block aperture D${tool}: ${w.message}` });
  }
  return plot;
}

function plotText(text: string, filetype: 'gerber' | 'drill'): Plot {
  const warnings: LibraryWarning[] = [];
  const parser = gerberParser({}) as unknown as ParserInternals;
  parser.on('warning', (w) => warnings.push(w));
  parser.format.filetype = filetype;
  parser._syncResult = [];
  parser._process(filetype === 'gerber' ? splitModeCodes(text) : dropZeroSet(text), filetype);
  parser._flush();
  const commands = parser._syncResult;

  const plotter = gerberPlotter({}) as unknown as PlotterInternals;
  plotter.on('warning', (w) => warnings.push(w));
  const objects: PlotObject[] = [];
  plotter.push = (o) => (objects.push(o), true);
  const fail = (error?: Error) => {
    if (error) throw error;
  };
  for (const command of commands as { type: string }[]) {
    const centre = isOp(command) ? quarterArcAt(plotter, command) : null;
    if (!centre || !isOp(command)) {
      plotter._transform(command, null, fail);
      continue;
    }
    // The centre as a multi-quadrant offset, for this one arc (single-quadrant.ts says why).
    const [sx, sy] = plotter._pos;
    const arc = plotter._arc;
    plotter._transform({ type: 'set', prop: 'arc', value: 'm' }, null, fail);
    plotter._transform({ ...command, coord: { ...command.coord, i: centre[0] - sx, j: centre[1] - sy } }, null, fail);
    plotter._transform({ type: 'set', prop: 'arc', value: arc }, null, fail);
  }
  plotter._flush(fail);

  const size = objects[objects.length - 1]; // the plotter's flush ends with the image's size and units
  const units: Units = size?.type === 'size' ? size.units : (plotter.format.units ?? 'in');
  return { filetype, units, objects, commands: commands.length, warnings };
}
