// Stands in for the npm 'string_decoder' package in the browser build (an alias in app/vite.config.ts).
//
// Why: gerber-parser constructs a StringDecoder for its streaming `_transform`, which tracespace.ts never
// calls (it hands the parser whole strings through `_process`). The real package pulls in a Buffer
// polyfill; this one decodes bytes with the browser's TextDecoder should anything ever call it.

export class StringDecoder {
  readonly #decoder: TextDecoder;

  constructor(encoding = 'utf8') {
    this.#decoder = new TextDecoder(encoding === 'utf8' ? 'utf-8' : encoding);
  }

  write(chunk: string | Uint8Array): string {
    return typeof chunk === 'string' ? chunk : this.#decoder.decode(chunk, { stream: true });
  }

  end(chunk?: string | Uint8Array): string {
    return (chunk === undefined ? '' : this.write(chunk)) + this.#decoder.decode();
  }
}

export default { StringDecoder };
