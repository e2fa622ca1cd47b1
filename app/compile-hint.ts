// A Vite plugin: V8's explicit compile hint (`//# allFunctionsCalledOnLoad`, Chrome 136) at the top
// of the first load's script. Nearly every function in it runs as the page loads (the Svelte runtime,
// the app's shell); compiled lazily, each was compiled on the page's thread when first called, inside
// the load's tasks. With the hint, V8 compiles them all on a background thread as the script streams.
// `npx tsx bench/page-load-tasks.ts 20`, twice each way on the same build (issue 40): loads with a
// task over 50 ms, 8 and 5 of 20 without the hint, 0 and 3 of 20 with it. Other browsers read a comment.
import type { Plugin } from 'vite';

const HINT = '//# allFunctionsCalledOnLoad\n';

export function compileHint(): Plugin {
  return {
    name: 'compile-hint',
    apply: 'build',
    enforce: 'post',
    // After Vite's own additions to the chunk (its preload map opens the file): the hint must be its first line.
    generateBundle: {
      order: 'post',
      handler(_options, bundle) {
        for (const chunk of Object.values(bundle)) {
          if (chunk.type !== 'chunk' || !chunk.isEntry || chunk.code.startsWith(HINT)) continue;
          chunk.code = HINT + chunk.code;
          if (chunk.map) chunk.map.mappings = `;${chunk.map.mappings}`; // one more line above the code
        }
      },
    },
  };
}
