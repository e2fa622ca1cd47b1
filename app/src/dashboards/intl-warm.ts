// The renderer's first Intl number and date formats, made in a throwaway worker before the thermal
// chart's code (uPlot) makes its own as it evaluates. The first use of Intl loads the locale's data
// (ICU): 23–100 ms in one task of the page on a busy machine, its longest task of the load (issue 40).
// ICU keeps that data for the whole renderer process, so the page's own formats then take no time
// (measured in Chromium: 0 ms after a worker made them). Where no worker starts (a policy against blob
// workers, an old browser) or none answers within 2 s, the page makes them itself, each in an idle
// task of its own, as before.

const SOURCE = 'new Intl.NumberFormat(navigator.language).format(1.5);new Intl.DateTimeFormat().resolvedOptions();postMessage(0);';

/** Resolves once the locale's number and date data are loaded; `idle` waits for an idle task of the page. */
export function warmIntl(idle: () => Promise<unknown>, waitMs = 2000): Promise<void> {
  const onPage = async () => {
    await idle();
    new Intl.NumberFormat(navigator.language).format(1.5);
    await idle();
    new Intl.DateTimeFormat().resolvedOptions();
  };
  let url: string | null = null;
  let worker: Worker;
  try {
    url = URL.createObjectURL(new Blob([SOURCE], { type: 'text/javascript' }));
    worker = new Worker(url);
  } catch {
    if (url) URL.revokeObjectURL(url);
    return onPage();
  }
  return new Promise<void>((resolve) => {
    let settled = false;
    const done = (inWorker: boolean) => {
      if (settled) return;
      settled = true;
      clearTimeout(late);
      worker.terminate();
      URL.revokeObjectURL(url!);
      resolve(inWorker ? undefined : onPage());
    };
    const late = setTimeout(() => done(false), waitMs);
    worker.onmessage = () => done(true);
    worker.onerror = () => done(false);
  });
}
