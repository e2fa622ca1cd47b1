// Work put off from the page load's tasks (issue 40): each long task of the load was some part of the
// page done in the same task as another. Parts mount a turn each; work nobody waits for runs when the
// page is idle; the fonts a canvas draws with are readied before the canvas first draws.

// The page's parts mounted one to a frame. Two parts whose code arrived together (the dashboards and
// the console share a chunk) mounted in one task, and the frame after laid out both: at page load,
// tasks of 60–90 ms where each part alone took 15–45. Each part waits its turn: the turn before it,
// then a frame (at most 200 ms: a background tab draws none), then a task of its own.
let last: Promise<void> = Promise.resolve();

/** A task after the next frame, and after every turn asked for before this one. */
export function nextTurn(): Promise<void> {
  const turn = last.then(afterFrame);
  last = turn;
  return turn;
}

function afterFrame(): Promise<void> {
  return new Promise((resolve) => {
    let done = false;
    const go = () => {
      if (done) return;
      done = true;
      clearTimeout(late);
      setTimeout(resolve); // out of the frame's callbacks: a task of its own, after its drawing
    };
    const late = setTimeout(go, 200);
    requestAnimationFrame(go);
  });
}

/** Runs `work` when the page is next idle (at most `latestMs` from now), or a second from now (at most) where there is no idle callback (Safari). */
export function whenIdle(work: () => void, latestMs = 2000): () => void {
  if (typeof requestIdleCallback === 'function') {
    const id = requestIdleCallback(work, { timeout: latestMs });
    return () => cancelIdleCallback(id);
  }
  const t = setTimeout(work, Math.min(1000, latestMs));
  return () => clearTimeout(t);
}

// The page's first text on a canvas finds and shapes its fonts: 13–30 ms inside whatever drew it
// first, the studio's rulers or the thermal chart's axes, each a long task of the page load. Drawn
// once on a canvas of a pixel, in a task of their own, the fonts are ready when the real drawing
// comes: the renderer keeps them for the whole page. (Here, in the first load, rather than a file of
// its own: shared by two lazy chunks, it became a 0.2 KB chunk and cost the ESP's image two blocks.)

const warmed = new Set<string>();

/** Whether every one of `fonts` has been drawn on this page already. */
export function canvasFontsWarm(fonts: readonly string[]): boolean {
  return fonts.every((f) => warmed.has(f));
}

/** Draws `sample` once in each font not yet drawn on this page. */
export function warmCanvasFonts(fonts: readonly string[], sample: string): void {
  const cold = fonts.filter((f) => !warmed.has(f));
  if (!cold.length) return;
  const ctx = document.createElement('canvas').getContext('2d');
  if (!ctx) return;
  for (const font of cold) {
    ctx.font = font;
    ctx.fillText(sample, 0, 0);
    warmed.add(font);
  }
}
