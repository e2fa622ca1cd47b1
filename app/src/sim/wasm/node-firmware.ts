// Node's way to the firmware module (tests, desktop hosts, the bench): the committed printer.wasm,
// compiled synchronously once per process.
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { firmwareModule, useFirmwareModule } from './firmware-module';

export const FIRMWARE_FILE = fileURLToPath(new URL('./printer.wasm', import.meta.url));

/** The module, compiled from printer.wasm the first time. */
export function nodeFirmware(): WebAssembly.Module {
  try {
    return firmwareModule();
  } catch {
    const module = new WebAssembly.Module(readFileSync(FIRMWARE_FILE));
    useFirmwareModule(module);
    return module;
  }
}

nodeFirmware();
