// A file as a project keeps it: the file itself as a data: URL (saved projects embed it); for a
// picture, its grey pixels decoded, which rasters are made from.

import { decodeImage } from '../image/decode';
import type { Gray } from '../image/gray';

/** Larger files are refused: a project embeds the file, and autosave keeps it in IndexedDB. */
export const MAX_ARTWORK_BYTES = 20 * 1024 * 1024;

export function dataUrl(file: Blob): Promise<string> {
  return new Promise((resolve, reject) => {
    const r = new FileReader();
    r.onload = () => resolve(String(r.result));
    r.onerror = () => reject(new Error('the file could not be read'));
    r.readAsDataURL(file);
  });
}

export function checkSize(file: Blob): void {
  if (file.size > MAX_ARTWORK_BYTES) throw new Error(`the file is ${(file.size / 1048576).toFixed(1)} MB; at most ${MAX_ARTWORK_BYTES / 1048576} MB can be embedded in a project`);
}

export async function readPicture(file: Blob): Promise<{ src: string; gray: Gray }> {
  checkSize(file);
  const gray = await decodeImage(file);
  return { src: await dataUrl(file), gray };
}

/** A picture embedded in a project, decoded again. */
export async function grayOf(src: string): Promise<Gray> {
  if (!src.startsWith('data:')) throw new Error('a project picture must be embedded as a data: URL');
  return decodeImage(await (await fetch(src)).blob());
}
