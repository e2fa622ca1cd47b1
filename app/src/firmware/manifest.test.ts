import { describe, expect, it } from 'vitest';
import { fetchPart, imagesFor, ManifestError, parseManifest, sha256 } from './manifest';

const hex = new TextEncoder().encode(':00000001FF\n');

describe('the images manifest', () => {
  it('names images by board; the old-bootloader Nano takes the Nano image', async () => {
    const m = parseManifest({ images: [{ board: 'nano', version: '0.2.0', built: 'PlatformIO', parts: [{ file: 'nano.hex', offset: 0, sha256: await sha256(hex), bytes: hex.length }] }] });
    expect(imagesFor(m, 'nano-old')).toHaveLength(1);
    expect(imagesFor(m, 'mega')).toHaveLength(0);
  });

  it.each([
    [{}, /no list/],
    [{ images: [{ board: 'uno', version: '1', parts: [] }] }, /no board/],
    [{ images: [{ board: 'mega', version: '1', parts: [] }] }, /no version or no files/],
    [{ images: [{ board: 'mega', version: '1', parts: [{ file: 'm.hex', offset: 0, sha256: 'abc' }] }] }, /SHA-256/],
  ])('refuses %j', (json, message) => {
    expect(() => parseManifest(json)).toThrow(message);
  });

  it('refuses a download whose hash is not the manifest\'s', async () => {
    const part = { file: 'nano.hex', offset: 0, sha256: await sha256(hex), bytes: hex.length };
    const serve = (body: Uint8Array) => (async () => new Response(body as Uint8Array<ArrayBuffer>)) as unknown as typeof fetch;
    expect(await fetchPart(new URL('http://x/firmware/'), part, serve(hex))).toEqual(hex);
    await expect(fetchPart(new URL('http://x/firmware/'), part, serve(new TextEncoder().encode(':00000001FE\n')))).rejects.toThrow(ManifestError);
  });
});
