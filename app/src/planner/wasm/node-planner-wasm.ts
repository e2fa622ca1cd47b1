// Node's way to the planner module (tests, the bench, desktop scripts): the committed planner.wasm
// beside this file, started synchronously once per process, on import (Vitest's setup file).
import { readFileSync } from 'node:fs';
import { loadPlannerWasm } from '../planner-wasm';

export const PLANNER_WASM_FILE = new URL('./planner.wasm', import.meta.url);

/** Loads the module from planner.wasm; later calls find it loaded. */
export function loadNodePlannerWasm(): void {
  loadPlannerWasm(readFileSync(PLANNER_WASM_FILE));
}

loadNodePlannerWasm();
