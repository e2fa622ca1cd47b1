// The painted cells in a project file: deflated (most of a bed is empty, so a 4096² grid of
// 16 MB shrinks to a few KB) and then base64, with the browser's own CompressionStream.

/** Bytes fed to the stream between the page's other tasks: a whole bed's 16 MB in one go held the page for 0.2 s. */
const CHUNK = 256 * 1024;

async function pipe(bytes: Uint8Array, stream: CompressionStream | DecompressionStream): Promise<Uint8Array> {
  const out = new Response(stream.readable).arrayBuffer();
  const writer = stream.writable.getWriter();
  for (let i = 0; i < bytes.length; i += CHUNK) {
    await writer.write(bytes.subarray(i, i + CHUNK) as Uint8Array<ArrayBuffer>);
    if (i + CHUNK < bytes.length) await new Promise((r) => setTimeout(r));
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
