// Undo and redo for a dose grid. An edit saves each 64 × 64 tile the first time it touches it, so
// a stroke across a 4096² grid costs only the tiles it crosses, and a flood fill no more than the
// area it fills. Steps that are not cells (the project's objects) share the same timeline.

import type { Box, DoseGrid } from './grid';

export type { Box };

const TILE = 64;

/** The cells a set of saved tiles covers, or null for none. */
function tilesBox(g: DoseGrid, tiles: Map<number, Uint8Array>): Box | null {
  const tilesX = Math.ceil(g.cols / TILE);
  let box: Box | null = null;
  for (const key of tiles.keys()) {
    const x0 = (key % tilesX) * TILE, y0 = Math.floor(key / tilesX) * TILE;
    const x1 = Math.min(g.cols, x0 + TILE) - 1, y1 = Math.min(g.rows, y0 + TILE) - 1;
    box = box ? { x0: Math.min(box.x0, x0), y0: Math.min(box.y0, y0), x1: Math.max(box.x1, x1), y1: Math.max(box.y1, y1) } : { x0, y0, x1, y1 };
  }
  return box;
}

interface Patch {
  /** Tile index → its cells before the edit (and, once undone, after it). */
  tiles: Map<number, Uint8Array>;
  label: string;
}

/** A step outside the cells: `swap` exchanges what it saved with what is, so it undoes and then redoes. */
export interface Swap {
  label: string;
  swap(): void;
}

type Step = Patch | Swap;

export class Edit {
  readonly #grid: DoseGrid;
  readonly tiles = new Map<number, Uint8Array>();
  readonly #tilesX: number;

  constructor(grid: DoseGrid, readonly label: string) {
    this.#grid = grid;
    this.#tilesX = Math.ceil(grid.cols / TILE);
  }

  /** Call before writing any cell of the box [x0, x1] × [y0, y1] (clipped to the grid). */
  touch(x0: number, y0: number, x1: number, y1: number): void {
    const g = this.#grid;
    const tx0 = Math.max(0, Math.floor(Math.min(x0, x1) / TILE)), tx1 = Math.min(this.#tilesX - 1, Math.floor(Math.max(x0, x1) / TILE));
    const ty0 = Math.max(0, Math.floor(Math.min(y0, y1) / TILE)), ty1 = Math.min(Math.ceil(g.rows / TILE) - 1, Math.floor(Math.max(y0, y1) / TILE));
    for (let ty = ty0; ty <= ty1; ty++)
      for (let tx = tx0; tx <= tx1; tx++) {
        const key = ty * this.#tilesX + tx;
        if (!this.tiles.has(key)) this.tiles.set(key, copyTile(g, tx, ty));
      }
  }

  /** The cells this edit may have changed: the tiles it saved. */
  box(): Box | null {
    return tilesBox(this.#grid, this.tiles);
  }

  /** Writes a cell, saving its tile first. */
  set(x: number, y: number, dose: number): void {
    if (!this.#grid.inside(x, y)) return;
    this.touch(x, y, x, y);
    this.#grid.cells[y * this.#grid.cols + x] = dose;
  }
}

/** A saved tile with no dose in it, kept as no bytes: a whole-bed fill of a blank bed saved 16 MB in 4 000 tiles (issue 40's long tasks). */
const BLANK = new Uint8Array(0);

function copyTile(g: DoseGrid, tx: number, ty: number): Uint8Array {
  const w = Math.min(TILE, g.cols - tx * TILE), h = Math.min(TILE, g.rows - ty * TILE);
  const cells = g.cells;
  if (blankTile(cells, g.cols, tx * TILE, ty * TILE, w, h)) return BLANK;
  const out = new Uint8Array(w * h);
  for (let y = 0; y < h; y++) out.set(cells.subarray((ty * TILE + y) * g.cols + tx * TILE, (ty * TILE + y) * g.cols + tx * TILE + w), y * w);
  return out;
}

/**
 * Whether the w × h cells from (x, y) hold no dose: four cells a word where a row's cells start on a
 * word. A byte at a time, a whole-bed fill's check of 16 M blank cells took 60 ms of the page's
 * thread on a busy machine (issue 40's long tasks).
 */
function blankTile(cells: Uint8Array, cols: number, x: number, y: number, w: number, h: number): boolean {
  const words = new Uint32Array(cells.buffer, 0, cells.buffer.byteLength >> 2);
  for (let r = 0; r < h; r++) {
    let i = cells.byteOffset + (y + r) * cols + x; // a byte of the buffer
    const end = i + w;
    for (; i < end && i & 3; i++) if (cells[i - cells.byteOffset] !== 0) return false;
    for (const last = end >> 2; i >> 2 < last; i += 4) if (words[i >> 2] !== 0) return false;
    for (; i < end; i++) if (cells[i - cells.byteOffset] !== 0) return false;
  }
  return true;
}

/** Swaps the saved tiles with the grid's, so the same patch undoes and then redoes. */
function swap(g: DoseGrid, tiles: Map<number, Uint8Array>): void {
  const tilesX = Math.ceil(g.cols / TILE);
  for (const [key, saved] of tiles) {
    const tx = key % tilesX, ty = Math.floor(key / tilesX);
    const now = copyTile(g, tx, ty);
    const w = Math.min(TILE, g.cols - tx * TILE), h = Math.min(TILE, g.rows - ty * TILE);
    for (let y = 0; y < h; y++) {
      const at = (ty * TILE + y) * g.cols + tx * TILE;
      if (saved === BLANK) g.cells.fill(0, at, at + w);
      else g.cells.set(saved.subarray(y * w, (y + 1) * w), at);
    }
    tiles.set(key, now);
  }
}

export class History {
  #undo: Step[] = [];
  #redo: Step[] = [];
  #bytes = 0;
  /** The cells the last undo, redo or revert rewrote. */
  lastChanged: Box | null = null;

  /** Keeps at most `maxBytes` of saved tiles (64 MB: sixteen whole 4096² grids). */
  constructor(readonly grid: DoseGrid, readonly maxBytes = 64 * 1024 * 1024) {}

  begin(label: string): Edit {
    return new Edit(this.grid, label);
  }

  /** Records a finished edit; an edit that touched nothing is not a step. */
  commit(edit: Edit): void {
    if (edit.tiles.size === 0) return;
    this.#push({ tiles: edit.tiles, label: edit.label });
  }

  /** Records a step outside the cells, already done. */
  record(step: Swap): void {
    this.#push(step);
  }

  #push(step: Step): void {
    this.#undo.push(step);
    this.#bytes += size(step);
    for (const p of this.#redo) this.#bytes -= size(p);
    this.#redo = [];
    while (this.#bytes > this.maxBytes && this.#undo.length > 1) this.#bytes -= size(this.#undo.shift()!);
  }

  /** Takes back an edit that is not to be a step (a stroke that turned into a pinch). */
  revert(edit: Edit): void {
    this.lastChanged = tilesBox(this.grid, edit.tiles);
    swap(this.grid, edit.tiles);
    edit.tiles.clear();
  }

  get canUndo(): boolean {
    return this.#undo.length > 0;
  }
  get canRedo(): boolean {
    return this.#redo.length > 0;
  }
  /** What undo would take back, for the menu. */
  get undoLabel(): string | null {
    return this.#undo.at(-1)?.label ?? null;
  }

  undo(): boolean {
    return this.#swapTop(this.#undo, this.#redo);
  }

  redo(): boolean {
    return this.#swapTop(this.#redo, this.#undo);
  }

  /** Swaps the newest step of `from` with the grid's tiles, and keeps it on `to` to go back. */
  #swapTop(from: Step[], to: Step[]): boolean {
    const p = from.pop();
    if (!p) return false;
    if ('tiles' in p) {
      this.lastChanged = tilesBox(this.grid, p.tiles);
      swap(this.grid, p.tiles);
    } else {
      this.lastChanged = null;
      p.swap();
    }
    to.push(p);
    return true;
  }
}

/** The bytes a step keeps: a step outside the cells keeps references, counted as nothing. */
function size(step: Step): number {
  let n = 0;
  if ('tiles' in step) for (const t of step.tiles.values()) n += t.length;
  return n;
}
