// The painted cells in a project file: deflated (most of a bed is empty, so a 4096² grid of
// 16 MB shrinks to a few KB) and then base64, with the browser's own CompressionStream.

/** Bytes fed to the stream between the page's other tasks: a whole bed's 16 MB in one go held the page for 0.2 s. */
const CHUNK = 256 * 1024;

/** Words read between the page's other tasks: a whole bed's 4 M words at once held the page 57 ms on a busy machine. */
const WORDS_A_SLICE = 1 << 19;

/** Lets the page's other tasks run: scheduler.yield where there is one (it keeps this work's place in the queue). */
const yieldToPage = (): Promise<unknown> => (globalThis as { scheduler?: { yield?: () => Promise<void> } }).scheduler?.yield?.() ?? new Promise((r) => setTimeout(r));

/**
 * Whether no cell is painted. Read four cells a word, half a million words at a time with the page's
 * other tasks between: a byte at a time, a whole bed's 16 M cells held the page for 70 ms at every
 * autosave on a busy machine, a word at a time in one go still 57 ms (issue 40's long tasks).
 */
export async function isBlank(cells: Uint8Array, wordsPerSlice = WORDS_A_SLICE): Promise<boolean> {
  const aligned = cells.byteOffset % 4 === 0;
  const words = aligned ? new Uint32Array(cells.buffer, cells.byteOffset, cells.length >> 2) : new Uint32Array(0);
  for (let start = 0; start < words.length; start += wordsPerSlice) {
    if (start > 0) await yieldToPage();
    const end = Math.min(words.length, start + wordsPerSlice);
    for (let i = start; i < end; i++) if (words[i] !== 0) return false;
  }
  for (let i = words.length << 2; i < cells.length; i++) if (cells[i] !== 0) return false;
  return true;
}

async function pipe(bytes: Uint8Array, stream: CompressionStream | DecompressionStream): Promise<Uint8Array> {
  const out = new Response(stream.readable).arrayBuffer();
  const writer = stream.writable.getWriter();
  for (let i = 0; i < bytes.length; i += CHUNK) {
    await writer.write(bytes.subarray(i, i + CHUNK) as Uint8Array<ArrayBuffer>);
    if (i + CHUNK < bytes.length) await yieldToPage();
  }
  await writer.close().catch(() => {}); // a damaged input fails the output, which says so
  return new Uint8Array(await out);
}

function toBase64(bytes: Uint8Array): string {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

function fromBase64(text: string): Uint8Array {
  const s = atob(text);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

export async function packCells(cells: Uint8Array): Promise<string> {
  return toBase64(await pipe(cells, new CompressionStream('deflate-raw')));
}

/** The cells back, exactly `length` of them, or an error that says what is wrong. */
export async function unpackCells(text: string, length: number): Promise<Uint8Array> {
  let packed: Uint8Array;
  try {
    packed = fromBase64(text);
  } catch {
    throw new Error('is not base64');
  }
  let cells: Uint8Array;
  try {
    cells = await pipe(packed, new DecompressionStream('deflate-raw'));
  } catch {
    throw new Error('is not deflated data: the file is damaged');
  }
  if (cells.length !== length) throw new Error(`holds ${cells.length} cells, not the ${length} its size says`);
  return cells;
}
