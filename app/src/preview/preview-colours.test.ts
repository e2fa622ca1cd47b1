import { describe, expect, it } from 'vitest';
import { doseColour, dosePixel, LED_COLOURS, pixelWord } from './preview-colours';

describe('the preview\'s colours as pixel words', () => {
  const bytes = (word: number) => Array.from(new Uint8Array(new Uint32Array([word]).buffer));
  it('are the same colours as doseColour, opaque, byte for byte as ImageData holds them', () => {
    for (const share of [-1, 0, 0.001, 0.25, 1 / 3, 0.5, 0.999, 1, 7])
      expect(bytes(dosePixel(share)), String(share)).toEqual([...doseColour(share), 255]);
    for (let k = 0; k <= 1000; k++) expect(bytes(dosePixel(k / 1000)).slice(0, 3)).toEqual(doseColour(k / 1000));
    expect(bytes(pixelWord(LED_COLOURS[1]))).toEqual([...LED_COLOURS[1], 255]);
  });
});
