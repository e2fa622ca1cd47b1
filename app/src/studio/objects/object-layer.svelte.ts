// The project's objects in the editor: the list, the selection, moving, resizing, turning and
// mirroring, and every change as one undo step in the grid's history; the job's resist polarity.
// Rasters are cached per object and remade only when what they show changes, not when it moves.

import type { History } from '../grid/history';
import type { DoseGrid } from '../grid/grid';
import { centredAt, exposes, keepsAspect, moved, objectAt, resized, type Corner, type Rect, type StudioObject } from './objects';
import { mirrored, turned } from './orientation';
import { compose, composeSoon, rasterOf, type Polarity, type Raster, type ReadyArtwork } from './raster';
import { textRaster } from './text-raster';

/** An object before it has its id. */
export type NewObject = StudioObject extends infer O ? (O extends StudioObject ? Omit<O, 'id'> : never) : never;

type Drag = { corner: Corner | null; from: { x: number; y: number }; start: Rect; before: StudioObject[] };

/** Same picture, text or frame at the same size: only the place differs. */
function sameLook(a: StudioObject, b: StudioObject): boolean {
  for (const k of Object.keys(a) as (keyof StudioObject)[]) if (k !== 'x' && k !== 'y' && a[k] !== b[k]) return false;
  return true;
}

export class ObjectLayer {
  objects = $state.raw<StudioObject[]>([]);
  selectedId = $state<number | null>(null);
  /** Bumped when an artwork's file is read, so views redraw it. */
  revision = $state(0);
  /** Negative resist (dry film): the artwork is exposed; positive: what it does not cover. */
  polarity = $state<Polarity>('negative');
  #nextId = 1;
  #drag: Drag | null = null;
  #rasters = new Map<number, { of: StudioObject; polarity: Polarity; raster: Raster }>();
  #artworks = new Map<string, ReadyArtwork>();

  constructor(private readonly history: History, private readonly cols: number, private readonly rows: number, private readonly onStep: () => void) {}

  get selected(): StudioObject | null {
    return this.objects.find((o) => o.id === this.selectedId) ?? null;
  }

  /** An artwork read from its file, known by its data: URL. */
  addArtwork(src: string, artwork: ReadyArtwork): void {
    this.#artworks.set(src, artwork);
    artwork.whenDrawn?.(() => this.revision++);
    this.revision++;
  }

  /** Once every exposing object's raster is in (those drawn off the page's thread take a while): what a job is made from. */
  async settled(): Promise<void> {
    for (const o of this.objects) {
      if (!exposes(o) || o.kind === 'text' || o.kind === 'frame') continue;
      await this.#artworks.get(o.src)?.settle?.(o, this.polarity);
    }
  }

  artwork(src: string): ReadyArtwork | undefined {
    return this.#artworks.get(src);
  }

  add(o: NewObject, label = `add ${o.kind}`): StudioObject {
    const made = { ...o, id: this.#nextId++ } as StudioObject;
    this.#change(label, [...this.objects, made]);
    this.selectedId = made.id;
    return made;
  }

  /** A new box of w × h cells centred on a cell, kept on the bed. */
  boxAt(cx: number, cy: number, w: number, h: number): Rect {
    return centredAt(cx, cy, Math.min(w, this.cols), Math.min(h, this.rows), this.cols, this.rows);
  }

  update(id: number, patch: Partial<StudioObject>, label = 'change'): void {
    const list = this.objects.map((o) => (o.id === id ? ({ ...o, ...patch, id } as StudioObject) : o));
    this.#change(label, list);
  }

  /** Changes several objects as one undo step (a two-sided board's sides, one in the job and the other out). */
  updateEach(patches: ReadonlyMap<number, Partial<StudioObject>>, label = 'change'): void {
    this.#change(label, this.objects.map((o) => (patches.has(o.id) ? ({ ...o, ...patches.get(o.id), id: o.id } as StudioObject) : o)));
  }

  remove(id: number): void {
    this.#change('delete', this.objects.filter((o) => o.id !== id));
    if (this.selectedId === id) this.selectedId = null;
  }

  /** A quarter turn clockwise (1) or anticlockwise (-1) about the object's middle. */
  turn(id: number, by: 1 | -1): void {
    const o = this.objects.find((x) => x.id === id);
    if (o) this.update(id, turned(o, by), by > 0 ? 'turn right' : 'turn left');
  }

  /** Mirrors the object across the bed's X (left to right) or Y (top to bottom). */
  mirror(id: number, axis: 'x' | 'y'): void {
    const o = this.objects.find((x) => x.id === id);
    if (o) this.update(id, mirrored(o, axis), `mirror ${axis.toUpperCase()}`);
  }

  /** Puts the object on top of the others or under them. */
  restack(id: number, toTop: boolean): void {
    const o = this.objects.find((x) => x.id === id);
    if (!o) return;
    const rest = this.objects.filter((x) => x !== o);
    this.#change(toTop ? 'bring to front' : 'send to back', toTop ? [...rest, o] : [o, ...rest]);
  }

  /** A project's objects, opened: no undo step (the history starts over with the project). */
  load(objects: StudioObject[], polarity: Polarity = 'negative'): void {
    this.objects = objects;
    this.polarity = polarity;
    this.#nextId = Math.max(0, ...objects.map((o) => o.id)) + 1;
    this.selectedId = null;
    this.#rasters.clear();
  }

  /**
   * Selects what lies under the cell, and starts moving it, or resizing it by `corner`. `reach`
   * is how many cells the pointer's few pixels span at this zoom.
   */
  press(cell: { x: number; y: number }, corner: Corner | null, reach = 0): boolean {
    const hit = corner ? this.selected : objectAt(this.objects, cell.x, cell.y, reach);
    this.selectedId = hit?.id ?? null;
    if (!hit) return false;
    this.#drag = { corner, from: cell, start: { x: hit.x, y: hit.y, w: hit.w, h: hit.h }, before: this.objects };
    return true;
  }

  dragTo(cell: { x: number; y: number }): void {
    const d = this.#drag, o = this.selected;
    if (!d || !o) return;
    const box = d.corner
      ? resized(d.start, d.corner, cell, keepsAspect(o))
      : moved(d.start, cell.x - d.from.x, cell.y - d.from.y, this.cols, this.rows);
    this.objects = this.objects.map((x) => (x.id === o.id ? ({ ...x, ...box } as StudioObject) : x));
  }

  /** Ends a drag: one undo step if anything moved. */
  release(): void {
    const d = this.#drag;
    this.#drag = null;
    if (!d || d.before === this.objects) return;
    const after = this.objects;
    this.objects = d.before;
    this.#change(d.corner ? 'resize' : 'move', after);
  }

  cancelDrag(): void {
    if (this.#drag) this.objects = this.#drag.before;
    this.#drag = null;
  }

  /** Moves the selection by whole cells (the arrow keys). */
  nudge(dx: number, dy: number): void {
    const o = this.selected;
    if (o) this.update(o.id, moved(o, dx, dy, this.cols, this.rows), 'move');
  }

  /** The object's doses at its size, or null while its artwork is still being read. */
  raster(o: StudioObject): Raster | null {
    const kept = this.#rasters.get(o.id);
    if (kept && kept.polarity === this.polarity && sameLook(kept.of, o)) return kept.raster;
    const raster = rasterOf(o, { artwork: (src) => this.#artworks.get(src), text: textRaster }, this.polarity);
    if (raster) this.#rasters.set(o.id, { of: o, polarity: this.polarity, raster });
    return raster;
  }

  /**
   * What to draw for the object: its raster and that raster's size. While a resize is dragged, or
   * while a new raster is drawn off the page's thread, the raster made before it is drawn stretched.
   */
  drawable(o: StudioObject): { raster: Raster; w: number; h: number } | null {
    const kept = this.#rasters.get(o.id);
    if (kept && this.#drag) return { raster: kept.raster, w: kept.of.w, h: kept.of.h };
    const raster = this.raster(o);
    if (raster) return { raster, w: o.w, h: o.h };
    // Its new raster is being drawn in the work worker: the one before it stands in until it is in.
    return kept ? { raster: kept.raster, w: kept.of.w, h: kept.of.h } : null;
  }

  composed(paint: DoseGrid): DoseGrid {
    return compose(paint, this.objects, (o) => this.raster(o), this.polarity);
  }

  /** The same, the page's other tasks let run between its steps. */
  composedSoon(paint: DoseGrid, pause: () => Promise<unknown>): Promise<DoseGrid> {
    return composeSoon(paint, this.objects, (o) => this.raster(o), this.polarity, pause);
  }

  #change(label: string, next: StudioObject[]): void {
    let saved = this.objects;
    this.objects = next;
    this.history.record({
      label,
      swap: () => {
        [this.objects, saved] = [saved, this.objects];
        if (!this.selected) this.selectedId = null;
      },
    });
    for (const id of this.#rasters.keys()) if (!this.objects.some((o) => o.id === id) && !saved.some((o) => o.id === id)) this.#rasters.delete(id);
    this.onStep();
  }
}
