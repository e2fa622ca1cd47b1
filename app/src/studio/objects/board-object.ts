// A board object's double-sided workflow, as pure arithmetic: the bottom side as a second object
// mirrored about the flip axis the user chooses, which side a job exposes (one at a time: the board
// is turned over between them), where a registration mark lies on the bed, and the move that puts
// a mark under the head ("set the job origin here").
import type { BoardLayerKind, BoardObject, DrillClear, Rect, StudioObject } from './objects';
import { frameSize, mirrored } from './orientation';

/** How the board is turned over: about a vertical line (its left and right swap) or a horizontal one. */
export type FlipAxis = 'left-right' | 'top-bottom';
/** Where that line lies: the board's middle (it turns over in place) or one of its edges. */
export type FlipAt = 'centre' | 'start' | 'end';

/** The choices a new board starts with (copperGuessed: when the top copper was taken from what it draws). */
export type NewBoardFields = Pick<BoardObject, 'layers' | 'drillClear' | 'marks' | 'copperGuessed'>;

/**
 * A new board's choices: the top copper exposed (else the bottom copper; with no copper at all, the first
 * file read that is neither drill nor outline, else the first read that is not drill, so something is on the
 * bed to expose), drill dots left unexposed where there are holes. `from`: how the kind was found ('content':
 * from what the file draws, not from what it says; 'unread': the file could not be read).
 */
export function newBoardFields(files: readonly { file: string; kind: BoardLayerKind; from?: string }[]): NewBoardFields {
  const kinds = files.map((f) => f.kind);
  const copper = kinds.includes('copper-top') ? 'copper-top' : kinds.includes('copper-bottom') ? 'copper-bottom' : null;
  const drawn = (i: number) => files[i].from !== 'unread' && kinds[i] !== 'drill';
  const artwork = kinds.findIndex((k, i) => drawn(i) && k !== 'outline');
  const first = copper ? -1 : artwork >= 0 ? artwork : kinds.findIndex((_, i) => drawn(i));
  const exposed = (i: number) => (copper ? kinds[i] === copper : i === first);
  const drillClear: DrillClear = kinds.includes('drill') ? 'unexposed-dot' : 'none';
  // The copper exposed, when it was taken from what it draws (numbered files may give a bottom copper too).
  const guessed = copper && files.find((f) => f.from === 'content' && f.kind === copper);
  return { layers: files.map(({ file, kind }, i) => ({ file, kind, expose: exposed(i) })), drillClear, marks: [], ...(guessed && { copperGuessed: guessed.file }) };
}

/** Whether any file of the board is taken for copper: if not, the board says so. */
export const hasCopper = (o: Pick<BoardObject, 'layers'>): boolean => o.layers.some((l) => l.kind === 'copper-top' || l.kind === 'copper-bottom');

/**
 * The bottom side of the board lying as the board will once turned over about the axis: mirrored
 * across it, its box reflected about the line (in place for the centre), exposing the bottom copper.
 * It starts left out of the job: the top side is exposed first, and the board turned over after.
 */
export function bottomSide(o: BoardObject, axis: FlipAxis, at: FlipAt): Omit<BoardObject, 'id'> {
  const { id: _, ...rest } = o;
  const across = axis === 'left-right' ? 'x' : 'y';
  const side = across === 'x' ? o.w : o.h;
  const shift = at === 'centre' ? 0 : at === 'start' ? -side : side;
  return {
    ...rest,
    ...mirrored(o, across),
    name: `${o.name} (bottom)`,
    [across]: o[across] + shift,
    layers: o.layers.map((l) => ({ ...l, expose: l.kind === 'copper-bottom' })),
    leftOut: true,
  };
}

export type Side = 'top' | 'bottom';

/** Which side of the board the object exposes: by its exposed layers' kinds, else mirrored (as the board lies turned over) or not. */
export function sideOf(o: BoardObject): Side {
  const exposed = o.layers.filter((l) => l.expose).map((l) => l.kind);
  if (exposed.some((k) => k.endsWith('-bottom'))) return 'bottom';
  if (exposed.some((k) => k.endsWith('-top'))) return 'top';
  return o.mirror ? 'bottom' : 'top';
}

/** A board placed more than once (its top and bottom sides): its objects in the order they were made, and which of them the job exposes. */
export interface TwoSided {
  /** The board's name, as its first object has it. */
  name: string;
  sides: { id: number; name: string; side: Side; inJob: boolean }[];
}

/** The sides placed of the board whose files are `src`: its objects. */
export function boardSides(objects: readonly StudioObject[], src: string): TwoSided {
  const list = objects.filter((o): o is BoardObject => o.kind === 'board' && o.src === src);
  return { name: list[0]?.name ?? '', sides: list.map((o) => ({ id: o.id, name: o.name, side: sideOf(o), inJob: !o.leftOut })) };
}

/** The boards of the drawing placed as more than one side (objects of the same files). */
export function twoSidedBoards(objects: readonly StudioObject[]): TwoSided[] {
  const srcs = new Set(objects.flatMap((o) => (o.kind === 'board' ? [o.src] : [])));
  return [...srcs].map((src) => boardSides(objects, src)).filter((b) => b.sides.length > 1);
}

/** What the job exposes of a two-sided board ("the top side of board demo"), or null when not one side. */
export function sideInJob(b: TwoSided): string | null {
  const inJob = b.sides.filter((s) => s.inJob);
  return inJob.length === 1 ? `the ${inJob[0].side} side of board ${b.name}` : null;
}

/** The leftOut of each object of the board for a job that exposes only the side `id`. */
export function onlySide(b: TwoSided, id: number): Map<number, { leftOut: boolean }> {
  return new Map(b.sides.map((s) => [s.id, { leftOut: s.id !== id }]));
}

/**
 * Where a mark's centre lies on the bed, in cells (fractional: a cell's corner is whole). `windowUm`
 * is the board's window, which the object's frame spans: the mark is mm from its lower left corner.
 */
export function markOnBed(o: BoardObject, mark: { x: number; y: number }, windowUm: { width: number; height: number }): { x: number; y: number } {
  const { w, h } = frameSize(o);
  let u = ((mark.x * 1000) / windowUm.width) * w;
  const v = (1 - (mark.y * 1000) / windowUm.height) * h;
  if (o.mirror) u = w - u;
  const turn = o.turn ?? 0;
  const [x, y] = turn === 0 ? [u, v] : turn === 1 ? [h - v, u] : turn === 2 ? [w - u, h - v] : [v, w - u];
  return { x: o.x + x, y: o.y + y };
}

/** The object's place with the mark under the head (µm on the bed), to the nearest cell. */
export function originAtHead(o: BoardObject, mark: { x: number; y: number }, windowUm: { width: number; height: number }, headUm: readonly number[], pitchUm: { x: number; y: number }): Pick<Rect, 'x' | 'y'> {
  const m = markOnBed(o, mark, windowUm);
  return { x: o.x + Math.round(headUm[0] / pitchUm.x - m.x), y: o.y + Math.round(headUm[1] / pitchUm.y - m.y) };
}
