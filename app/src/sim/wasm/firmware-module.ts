// The compiled firmware module (printer.wasm beside this file, committed: `npm start` needs no
// compiler, and `npm test` checks that the sources still build it byte for byte). Compiled once per
// page, worker or process; each simulated printer is an instance of it.

let compiled: WebAssembly.Module | null = null;

/** Where the module's bytes are: an asset of the app's build, or a file beside this one in Node. */
export const FIRMWARE_URL = new URL('./printer.wasm', import.meta.url);

/** Compiles the module from its bytes, or from its URL; later calls find it compiled. */
export async function loadFirmwareModule(bytes?: BufferSource): Promise<WebAssembly.Module> {
  if (!compiled) {
    compiled = bytes ? await WebAssembly.compile(bytes) : await WebAssembly.compileStreaming(fetch(FIRMWARE_URL));
  }
  return compiled;
}

/** Takes a module compiled elsewhere (Node compiles it synchronously from the file). */
export function useFirmwareModule(module: WebAssembly.Module): void {
  compiled = module;
}

/** The compiled module; loadFirmwareModule (or useFirmwareModule) must have run. */
export function firmwareModule(): WebAssembly.Module {
  if (!compiled) throw new Error('the firmware module is not loaded yet: await loadFirmwareModule() first');
  return compiled;
}
