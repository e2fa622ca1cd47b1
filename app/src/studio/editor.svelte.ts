// The grid editor's state: the machine's grid, its history, the tool in hand and the view.
// The canvas component turns pointer, wheel and key events into calls here.

import { DoseGrid } from './grid/grid';
import { History, type Box, type Edit } from './grid/history';
import { floodFill, line, rectangle, stamp } from './grid/tools';
import { fit, panBy, RULER, toCell, toScreen, zoomAt, type View } from './canvas/viewport';
import { bedOf, DEFAULT_CONFIG } from './machine-config';
import { ObjectLayer } from './objects/object-layer.svelte';
import { exposes, type Corner, type StudioObject } from './objects/objects';
import { textWidth } from './objects/text-raster';
import { boxSize, frameSize } from './objects/orientation';
import { typeKey } from './objects/typing';
import { freePlace } from './objects/placement';
import { handleAt } from './canvas/handles';
import type { Rect } from './objects/objects';

/** The Text tool's words until the user gives others: the first key typed replaces them. */
const PLACEHOLDER_TEXT = 'Text';
import { layOver, type Polarity } from './objects/raster';

export type Tool = 'brush' | 'eraser' | 'line' | 'rect' | 'rect-filled' | 'fill' | 'select' | 'text' | 'frame' | 'pan';

/** How near a corner handle, in screen pixels, a press takes it. */
const HANDLE = 8;
/** How far apart an import is placed from the objects already there, where the bed has room: two outlines edge to edge read as one. */
const PLACED_APART_MM = 2;

export interface BedGeometry {
  bedMm: { x: number; y: number };
  pitchUm: { x: number; y: number };
}

/** The Mega's defaults (CONFIG.md) until its own settings are read. */
export const DEFAULT_BED: BedGeometry = bedOf(DEFAULT_CONFIG);

export class GridEditor {
  grid: DoseGrid;
  history: History;
  /** The pictures, text and frames over the painted cells. */
  layer: ObjectLayer;
  /** What the text tool writes, in which font and how high (mm). */
  text = $state({ text: PLACEHOLDER_TEXT, font: 'sans-serif', bold: false, heightMm: 5 });
  /** The text object placed by the last click of the Text tool, taking the keys typed on the canvas. */
  typing = $state<{ id: number; fresh: boolean } | null>(null);
  tool = $state<Tool>('brush');
  size = $state(5);
  dose = $state(255);
  view = $state<View>({ scale: 1, x: 0, y: 0 });
  /** Bumped on every change of the cells, so views of them can follow. */
  revision = $state(0);
  canUndo = $state(false);
  canRedo = $state(false);
  /** Whether any cell has a dose: known after each finished edit, not during a stroke. */
  hasInk = $state(false);
  /** A line or rectangle being dragged: its corners, drawn as a preview until release. */
  preview = $state<{ x0: number; y0: number; x1: number; y1: number } | null>(null);
  /** Called with the box of cells an edit changed (the renderer's cache listens). */
  onCells: (x0: number, y0: number, x1: number, y1: number) => void = () => {};

  #edit: Edit | null = null;
  #last: { x: number; y: number } | null = null;
  #start: { x: number; y: number } | null = null;

  /** An empty bed, or a project's cells (as many as the bed has), objects and resist polarity. */
  constructor(readonly machine: BedGeometry = DEFAULT_BED, from?: { cells: Uint8Array; objects: StudioObject[]; polarity?: Polarity }) {
    this.grid = DoseGrid.forBed(machine.bedMm, machine.pitchUm);
    this.history = new History(this.grid);
    this.layer = new ObjectLayer(this.history, this.grid.cols, this.grid.rows, () => this.#syncHistory());
    if (from) {
      this.grid.cells.set(from.cells);
      this.layer.load(from.objects, from.polarity);
      this.#syncHistory();
    }
  }

  /** Nothing painted and no object placed, not even a guide frame. */
  get isEmpty(): boolean {
    return !this.hasInk && this.layer.objects.length === 0;
  }

  /** The cells the machine exposes: the painting with the objects laid over it. */
  composed(): DoseGrid {
    return this.layer.composed(this.grid);
  }

  /** The same, the page's other tasks let run between its steps. */
  composedSoon(pause: () => Promise<unknown>): Promise<DoseGrid> {
    return this.layer.composedSoon(this.grid, pause);
  }

  /** Millimetres to cells across (x) or down (y). */
  cells(mm: number, axis: 'x' | 'y' = 'x'): number {
    return Math.max(1, Math.round((mm * 1000) / this.machine.pitchUm[axis]));
  }

  /** The canvas's size in CSS pixels, as its component last measured it. */
  screen = { width: 0, height: 0 };

  fitTo(width: number, height: number): void {
    this.screen = { width, height };
    this.view = fit(this.grid.cols, this.grid.rows, width, height, 16, RULER);
  }

  /**
   * A place for a w × h object the pointer did not place (an import): free of every other object,
   * in view if there is room there (freePlace). The view follows one placed outside it.
   */
  freeBox(w: number, h: number): Rect {
    const a = toCell(this.view, RULER, RULER), b = toCell(this.view, this.screen.width, this.screen.height);
    const visible = { x: Math.ceil(a.x), y: Math.ceil(a.y), w: Math.floor(b.x - a.x), h: Math.floor(b.y - a.y) };
    const box = freePlace(this.layer.objects, w, h, visible, this.grid.cols, this.grid.rows, { x: this.cells(PLACED_APART_MM, 'x'), y: this.cells(PLACED_APART_MM, 'y') });
    const shown = box.x >= visible.x && box.y >= visible.y && box.x + box.w <= visible.x + visible.w && box.y + box.h <= visible.y + visible.h;
    if (!shown) {
      const at = toScreen(this.view, box.x + box.w / 2, box.y + box.h / 2);
      this.pan((RULER + this.screen.width) / 2 - at.x, (RULER + this.screen.height) / 2 - at.y);
    }
    return box;
  }

  zoom(factor: number, sx: number, sy: number): void {
    this.view = zoomAt(this.view, factor, sx, sy);
  }

  pan(dx: number, dy: number): void {
    this.view = panBy(this.view, dx, dy);
  }

  /** A pointer went down at screen (sx, sy): a stroke or a shape begins. */
  down(sx: number, sy: number): void {
    this.typing = null; // a click ends typing into a placed text
    if (this.tool === 'pan') return;
    if (this.tool === 'select') {
      this.layer.press(toCell(this.view, sx, sy), this.#cornerAt(sx, sy), HANDLE / this.view.scale);
      return;
    }
    const c = this.#cell(sx, sy);
    if (this.tool === 'text') {
      this.addText(c.x, c.y);
      return;
    }
    this.#edit = this.history.begin(this.tool);
    this.#start = c;
    this.#last = c;
    if (this.tool === 'brush' || this.tool === 'eraser') this.#stroke(c, c);
    else if (this.tool === 'fill') {
      if (floodFill(this.grid, this.#edit, c.x, c.y, this.dose)) this.#changedBox(this.#edit.box());
    } else this.preview = { x0: c.x, y0: c.y, x1: c.x, y1: c.y };
  }

  move(sx: number, sy: number): void {
    if (this.tool === 'select') this.layer.dragTo(toCell(this.view, sx, sy));
    if (!this.#edit || !this.#last || !this.#start) return;
    const c = this.#cell(sx, sy);
    if (this.tool === 'brush' || this.tool === 'eraser') this.#stroke(this.#last, c);
    else if (this.preview) this.preview = { x0: this.#start.x, y0: this.#start.y, x1: c.x, y1: c.y };
    this.#last = c;
  }

  up(): void {
    if (this.tool === 'select') this.layer.release();
    const e = this.#edit;
    if (!e) return;
    const p = this.preview;
    if (p && this.tool === 'frame') {
      this.#edit = this.#last = this.#start = null;
      this.preview = null;
      const { cols, rows } = this.grid;
      const x = Math.max(0, Math.min(p.x0, p.x1)), y = Math.max(0, Math.min(p.y0, p.y1)); // on the bed
      const w = Math.min(cols - 1, Math.max(p.x0, p.x1)) - x + 1, h = Math.min(rows - 1, Math.max(p.y0, p.y1)) - y + 1;
      if (w > 0 && h > 0) this.layer.add({ kind: 'frame', x, y, w, h, line: 0, dose: this.dose });
      this.tool = 'select';
      return;
    }
    if (p && this.tool === 'line') {
      line(this.grid, e, p.x0, p.y0, p.x1, p.y1, this.size, this.dose);
      this.#changed(Math.min(p.x0, p.x1) - this.size, Math.min(p.y0, p.y1) - this.size, Math.max(p.x0, p.x1) + this.size, Math.max(p.y0, p.y1) + this.size);
    } else if (p && (this.tool === 'rect' || this.tool === 'rect-filled')) {
      rectangle(this.grid, e, p.x0, p.y0, p.x1, p.y1, this.tool === 'rect-filled', this.size, this.dose);
      this.#changed(Math.min(p.x0, p.x1), Math.min(p.y0, p.y1), Math.max(p.x0, p.x1), Math.max(p.y0, p.y1));
    }
    this.history.commit(e);
    this.#edit = this.#last = this.#start = null;
    this.preview = null;
    this.#syncHistory();
  }

  /** Drops the stroke or shape in progress, leaving the grid as it was before it. */
  cancel(): void {
    this.layer.cancelDrag();
    const e = this.#edit;
    if (!e) return;
    this.history.revert(e);
    this.#edit = this.#last = this.#start = null;
    this.preview = null;
    this.#changedBox(this.history.lastChanged);
  }

  undo(): void {
    if (this.history.undo()) this.#afterHistory();
  }

  redo(): void {
    if (this.history.redo()) this.#afterHistory();
  }

  /** Puts doses into the grid as one undoable step (an import, a generated test strip). */
  place(doses: Uint8Array, width: number, height: number, atX: number, atY: number, label: string): void {
    const e = this.history.begin(label);
    const x0 = Math.max(0, atX), y0 = Math.max(0, atY);
    const x1 = Math.min(this.grid.cols - 1, atX + width - 1), y1 = Math.min(this.grid.rows - 1, atY + height - 1);
    if (x0 > x1 || y0 > y1) return;
    e.touch(x0, y0, x1, y1);
    for (let y = y0; y <= y1; y++)
      this.grid.cells.set(doses.subarray((y - atY) * width + (x0 - atX), (y - atY) * width + (x1 - atX) + 1), y * this.grid.cols + x0);
    this.history.commit(e);
    this.#changed(x0, y0, x1, y1);
    this.#syncHistory();
  }

  /**
   * A text object with the text tool's settings where the user clicked: it starts at the click and
   * is centred on it in height, so it grows to the right as it is typed. Then the keys typed on the
   * canvas go into it (`type`), until Enter, Escape or another click.
   */
  addText(cx: number, cy: number): void {
    const t = this.text;
    const h = Math.min(this.cells(t.heightMm, 'y'), this.grid.rows);
    const w = Math.min(textWidth(t, h), this.grid.cols);
    const x = Math.max(0, Math.min(this.grid.cols - w, cx));
    const y = Math.max(0, Math.min(this.grid.rows - h, Math.round(cy - h / 2)));
    const made = this.layer.add({ kind: 'text', x, y, w, h, text: t.text, font: t.font, bold: t.bold, dose: this.dose });
    this.tool = 'select';
    this.typing = { id: made.id, fresh: t.text === PLACEHOLDER_TEXT }; // words prepared in the panel are kept and typed on
  }

  /** A key pressed on the canvas while a placed text takes typing; false if it is not typing. */
  type(key: string, opts: { shift: boolean; mod: boolean }): boolean {
    const o = this.typing && this.layer.objects.find((x) => x.id === this.typing!.id);
    if (!o || o.kind !== 'text') return false;
    const r = typeKey(o.text, key, { fresh: this.typing!.fresh, ...opts });
    if (!r) return false;
    if (r.done) this.typing = null;
    else {
      this.typing = { id: o.id, fresh: false };
      // The text grows along its own frame's width: across the bed, or down it when turned.
      const next = { ...o, text: r.text }, h = frameSize(o).h;
      const room = (o.turn ?? 0) & 1 ? this.grid.rows - o.y : this.grid.cols - o.x;
      const box = boxSize(o, Math.max(1, Math.min(textWidth(next, h), room)), h);
      this.layer.update(o.id, { text: r.text, ...box }, 'type text');
    }
    return true;
  }

  /** Paints the object into the cells (one step) and takes it off the layer. */
  mergeDown(id: number): void {
    const o = this.layer.objects.find((x) => x.id === id);
    const r = o && this.layer.raster(o);
    if (!o || !r) return;
    const e = this.history.begin(`merge ${o.kind}`);
    e.touch(o.x, o.y, o.x + o.w - 1, o.y + o.h - 1); // clipped to the grid
    const covered = layOver(this.grid, o, r);
    this.history.commit(e);
    if (covered) this.#changed(covered.x0, covered.y0, covered.x1, covered.y1);
    this.layer.remove(id);
  }

  clear(): void {
    this.place(new Uint8Array(this.grid.cols * this.grid.rows), this.grid.cols, this.grid.rows, 0, 0, 'clear');
  }

  /** The selected object's corner handle under the screen point, if any. */
  #cornerAt(sx: number, sy: number): Corner | null {
    const o = this.layer.selected;
    return o ? handleAt(this.view, o, sx, sy) : null;
  }

  #cell(sx: number, sy: number): { x: number; y: number } {
    const c = toCell(this.view, sx, sy);
    return { x: Math.floor(c.x), y: Math.floor(c.y) };
  }

  #stroke(a: { x: number; y: number }, b: { x: number; y: number }): void {
    const dose = this.tool === 'eraser' ? 0 : this.dose;
    if (a.x === b.x && a.y === b.y) stamp(this.grid, this.#edit!, a.x, a.y, this.size, dose);
    else line(this.grid, this.#edit!, a.x, a.y, b.x, b.y, this.size, dose);
    const r = Math.ceil(this.size / 2);
    this.#changed(Math.min(a.x, b.x) - r, Math.min(a.y, b.y) - r, Math.max(a.x, b.x) + r, Math.max(a.y, b.y) + r);
  }

  #changed(x0: number, y0: number, x1: number, y1: number): void {
    this.onCells(x0, y0, x1, y1);
    this.revision++;
  }

  #afterHistory(): void {
    this.#changedBox(this.history.lastChanged);
    this.#syncHistory();
  }

  /** Only the tiles an edit saved are redrawn: undoing a stroke on a 4096² grid must not remake it all. */
  #changedBox(b: Box | null): void {
    if (b) this.#changed(b.x0, b.y0, b.x1, b.y1);
  }

  #syncHistory(): void {
    this.canUndo = this.history.canUndo;
    this.canRedo = this.history.canRedo;
    this.hasInk = this.layer.objects.some(exposes) || anyDose(this.grid.cells);
  }
}

/** A word at a time: an empty 4096² grid is read in a few milliseconds. */
function anyDose(cells: Uint8Array): boolean {
  const words = new Uint32Array(cells.buffer, cells.byteOffset, cells.length >> 2);
  for (let i = 0; i < words.length; i++) if (words[i]) return true;
  for (let i = words.length << 2; i < cells.length; i++) if (cells[i]) return true;
  return false;
}
