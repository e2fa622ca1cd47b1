// Artwork whose heavy work runs in the work worker (loaded on demand): a picture decoded there,
// a board's Gerber read there, and each object's raster drawn there, so the page never waits on
// them. The editor asks for a raster and gets null until it is in; then it redraws. Whatever
// fires or plans waits for every raster first (ObjectLayer.settled).

import { Cancelled, spawnWorker, WorkClient, type CallOptions } from '../../work/work-client';
import type { BoardRead, PictureRead } from '../../work/work-types';
import { ready } from './artwork';
import type { ArtworkObject } from './objects';
import { madeSprites, type Polarity, type Raster, type ReadyArtwork } from './raster';

/** The studio's worker: one for every picture and board, so what it has read serves them all. */
export const studioWork = new WorkClient(spawnWorker);

/** Rasters kept per artwork: the last few looks and sizes (a resize back and forth, an undo). */
const KEPT = 6;

/** What is drawn: everything of the object but where it lies, and its file (one artwork, one file; a picture's can be 27 MB). */
export function lookKey(o: ArtworkObject, polarity: Polarity): string {
  const { x: _x, y: _y, id: _id, src: _src, ...look } = o;
  return JSON.stringify([look, polarity]);
}

type Entry = { raster: Raster | null; error: Error | null; done: Promise<void> };

export function remoteArtwork(pixels: { width: number; height: number }, client: WorkClient = studioWork): ReadyArtwork {
  const drawn = new Map<string, Entry>();
  // Kept here, not on the object: the object may sit in Svelte state behind a proxy.
  let redraw = () => {};
  const art: ReadyArtwork = {
    pixels,
    whenDrawn: (f) => void (redraw = f),
    drawn: (o, polarity) => entry(o, polarity).raster,
    settle: async (o, polarity) => {
      const e = entry(o, polarity);
      await e.done;
      if (e.error) throw e.error;
    },
  };
  function entry(o: ArtworkObject, polarity: Polarity): Entry {
    const key = lookKey(o, polarity);
    const have = drawn.get(key);
    if (have) return have;
    const e: Entry = { raster: null, error: null, done: Promise.resolve() };
    e.done = client.call<{ raster: Raster; sprite: ImageBitmap | null }>({ kind: 'raster', object: { ...o }, polarity }).then(
      ({ raster, sprite }) => {
        if (sprite) madeSprites.set(raster, sprite);
        e.raster = raster;
        redraw();
      },
      (err: Error) => {
        if (err instanceof Cancelled) {
          drawn.delete(key); // the worker was ended (an import cancelled): asked again when next drawn
          redraw();
        } else {
          e.error = err; // an exposure waiting for it says so (settle)
          console.error(`the artwork could not be drawn: ${err.message}`);
        }
      },
    );
    if (drawn.size >= KEPT) drawn.delete(drawn.keys().next().value!);
    drawn.set(key, e);
    return e;
  }
  return art;
}

/** A picture embedded as a data: URL, decoded in the worker: its size in pixels and whether it is line art. */
export const readPicture = (src: string, opts?: CallOptions) => studioWork.call<PictureRead>({ kind: 'read-picture', src }, opts);

/** A board's files, read in the worker; also embedded as the object's data: URL. */
export const readBoard = (from: { src: string } | { files: { name: string; text: string }[] }, opts?: CallOptions) => studioWork.call<BoardRead>({ kind: 'read-board', ...from }, opts);

/** An artwork of a project opened again, known by its kind and embedded file. */
export async function readArtwork(o: Pick<ArtworkObject, 'kind' | 'src'>): Promise<ReadyArtwork> {
  if (o.kind === 'svg') {
    return ready(await (await import('./svg-artwork')).svgArtwork(o.src));
  }
  const { pixels } = o.kind === 'board' ? await readBoard({ src: o.src }) : await readPicture(o.src);
  return remoteArtwork(pixels);
}
