// The work worker's way to the planner module (planner-wasm.ts plannerReady): fetched once, a failed
// fetch said with the module's name, and the next request trying again, as after a redeploy that
// left the page on an old build whose module is gone, or a hub that lost the file.
import { readFileSync } from 'node:fs';
import { afterEach, describe, expect, it, vi } from 'vitest';
import { PLANNER_WASM_FILE } from './wasm/node-planner-wasm';

afterEach(() => {
  vi.unstubAllGlobals();
  vi.resetModules();
});

/** A fresh copy of planner-wasm.ts: the module not yet loaded, as in a new worker. */
async function freshPlanner(): Promise<typeof import('./planner-wasm')> {
  vi.resetModules();
  return import('./planner-wasm');
}

describe('the planner module, fetched by the work worker', () => {
  it('says which file failed, plans nothing meanwhile, and loads on the next try', async () => {
    const bytes = readFileSync(PLANNER_WASM_FILE);
    const answers = [new Response('not here', { status: 404 }), new Response(bytes, { status: 200 })];
    const fetch = vi.fn(async (url: URL | string) => {
      expect(String(url)).toMatch(/planner\.wasm$/);
      return answers.shift()!;
    });
    vi.stubGlobal('fetch', fetch);
    const wasm = await freshPlanner();
    await expect(wasm.plannerReady()).rejects.toThrow("the planner's module (planner.wasm) could not be loaded: HTTP 404. Reload the page if the app was updated");
    expect(() => wasm.moveTimeUs(1000, 100_000, 2_000_000)).toThrow(/not loaded/);
    await wasm.plannerReady();
    expect(wasm.moveTimeUs(100_000, 150_000, 3_000_000)).toBe(666_667 + 50_000);
    await wasm.plannerReady(); // loaded: no third fetch
    expect(fetch).toHaveBeenCalledTimes(2);
  });

  it('says so when the network itself fails, and when the bytes are no module', async () => {
    vi.stubGlobal('fetch', vi.fn(async () => {
      throw new TypeError('Failed to fetch');
    }));
    let wasm = await freshPlanner();
    await expect(wasm.plannerReady()).rejects.toThrow("the planner's module (planner.wasm) could not be loaded: Failed to fetch. Reload the page");
    // A server that answers every path with the page (a single-page host's fallback) gives HTML.
    vi.stubGlobal('fetch', vi.fn(async () => new Response('<!doctype html><title>UV</title>', { status: 200 })));
    wasm = await freshPlanner();
    await expect(wasm.plannerReady()).rejects.toThrow(/the planner's module \(planner\.wasm\) could not be loaded/);
  });
});
