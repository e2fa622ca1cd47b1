// How a scan job (exposure on the move) is described wherever it is shown: the dry run, the preview.

export function scanWords(passes: number, speedUmS: number, windowUs: number): string {
  const mmS = speedUmS / 1000;
  return `${passes} pass${passes === 1 ? '' : 'es'} at ${mmS.toFixed(mmS < 10 ? 2 : 1)} mm/s, a ${(windowUs / 1000).toFixed(2)} ms window per cell`;
}
