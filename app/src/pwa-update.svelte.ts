// The service worker's side in the page: registers it beside the page (the app may be served under any
// path, as https://OWNER.github.io/REPO/), tells it which version this page runs, and, when a deploy
// brings a new version, says so and lets it take over only while no job runs. Never reloads by itself.

/** How often an open page asks for a new version, besides when it comes back into view. */
const CHECK_EVERY_MS = 60 * 60 * 1000;

export class AppUpdate {
  /** A new version is installed: the next load runs it. */
  ready = $state(false);
  #waiting: ServiceWorker | null = null;

  /** Registers the worker: not in development (Vite serves the files fresh), nor in the ESP's image (no secure context, no worker). */
  async start(): Promise<void> {
    if (!import.meta.env.PROD || import.meta.env.MODE === 'esp' || !('serviceWorker' in navigator)) return;
    const sw = navigator.serviceWorker;
    // This module rides in the entry chunk: its URL names the version, and the worker keeps that
    // version's files while this page is open.
    const running = () => sw.controller?.postMessage({ type: 'running', entry: import.meta.url });
    sw.addEventListener('controllerchange', running);
    const registration = await sw.register('./sw.js', { scope: './' });
    running();
    const offer = (worker: ServiceWorker) => {
      this.#waiting = worker;
      this.ready = true;
    };
    // A first install is no update: there was no worker before it.
    const follow = (worker: ServiceWorker | null) => {
      if (!worker) return;
      if (worker.state === 'installed') {
        if (sw.controller) offer(worker);
        return;
      }
      worker.addEventListener('statechange', () => {
        if (worker.state === 'installed' && sw.controller) offer(worker);
      });
    };
    follow(registration.waiting);
    follow(registration.installing);
    registration.addEventListener('updatefound', () => follow(registration.installing));
    const check = () => void registration.update().catch(() => {}); // offline: nothing to hear
    document.addEventListener('visibilitychange', () => document.visibilityState === 'visible' && check());
    setInterval(check, CHECK_EVERY_MS);
  }

  /**
   * Lets the new version's worker take over; App calls it once no job runs. This page keeps running
   * the version it loaded, whose files the worker keeps while it is open.
   */
  takeOver(): void {
    this.#waiting?.postMessage({ type: 'skip-waiting' });
  }

  /** Loads the new version: once its worker has taken over, else the reload would get the old one again. */
  async reload(): Promise<void> {
    const sw = navigator.serviceWorker;
    if (this.#waiting && this.#waiting.state !== 'activated') {
      const taken = new Promise<void>((resolve) => {
        sw.addEventListener('controllerchange', () => resolve(), { once: true });
        setTimeout(resolve, 3000);
      });
      this.takeOver();
      await taken;
    }
    location.reload();
  }
}
