// The published images' manifest (firmware/manifest.json beside the app, written by
// scripts/firmware-manifest.mjs): which board each image is for, its version, where its files go, and
// each file's SHA-256, checked before anything is written.

import type { BoardId } from './chips';

export interface ImagePart {
  file: string;
  /** Where it goes in the chip's flash (the ESP's firmware at 0, its LittleFS image higher up). */
  offset: number;
  sha256: string;
  bytes: number;
}

export interface ManifestImage {
  board: 'nano' | 'mega' | 'esp8266' | 'esp32';
  version: string;
  /** How it was built: "PlatformIO" (the published images) or "Debian avr-gcc" (this machine's). */
  built: string;
  parts: ImagePart[];
  /** What such an image lacks, said beside it: the Debian Mega image has no SD card. */
  lacks?: string;
}

export interface Manifest {
  images: ManifestImage[];
}

export class ManifestError extends Error {}

const BOARDS = ['nano', 'mega', 'esp8266', 'esp32'];

export function parseManifest(json: unknown): Manifest {
  const m = json as Manifest;
  if (!m || !Array.isArray(m.images)) throw new ManifestError('the manifest has no list of images');
  for (const [i, image] of m.images.entries()) {
    const where = `image ${i + 1}`;
    if (!BOARDS.includes(image?.board)) throw new ManifestError(`${where} names no board this app knows`);
    if (typeof image.version !== 'string' || !Array.isArray(image.parts) || !image.parts.length) throw new ManifestError(`${where} has no version or no files`);
    for (const p of image.parts) {
      if (typeof p.file !== 'string' || !Number.isInteger(p.offset) || !/^[0-9a-f]{64}$/.test(p.sha256)) throw new ManifestError(`${where} has a file without a name, offset or SHA-256`);
    }
  }
  return m;
}

/** The manifest's images for a board the view offers (both Nano bootloaders take the Nano's image). */
export const imagesFor = (manifest: Manifest, board: BoardId) => manifest.images.filter((i) => i.board === (board === 'nano-old' ? 'nano' : board));

export async function sha256(bytes: Uint8Array): Promise<string> {
  const digest = await crypto.subtle.digest('SHA-256', bytes as Uint8Array<ArrayBuffer>);
  return Array.from(new Uint8Array(digest), (b) => b.toString(16).padStart(2, '0')).join('');
}

/** Fetches one part and checks it against the manifest: a damaged or replaced download is refused. */
export async function fetchPart(base: URL, part: ImagePart, fetcher: typeof fetch = fetch): Promise<Uint8Array> {
  const response = await fetcher(new URL(part.file, base));
  if (!response.ok) throw new ManifestError(`${part.file} could not be downloaded (HTTP ${response.status})`);
  const bytes = new Uint8Array(await response.arrayBuffer());
  if ((await sha256(bytes)) !== part.sha256) throw new ManifestError(`${part.file} is not the file the manifest names (its SHA-256 differs): the download was damaged`);
  return bytes;
}
