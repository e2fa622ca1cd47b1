// The app's service worker: the app's own files come from the cache, so it starts with no network
// at all (the printer's access point has no internet, and a laptop on the bench may have none).
// The printer's API (/status, /print, /ws, /wifi) always goes to the network. The build fills in
// PRECACHE, the app's files relative to the worker's scope (the app may live under any path, as
// https://OWNER.github.io/REPO/ does), and VERSION, a hash of them: a new build installs a new cache.
const PRECACHE = self.__PRECACHE__;
const VERSION = self.__VERSION__;
const PREFIX = 'uv-exposure-';
const CACHE = `${PREFIX}${VERSION}`;
// Which version each open page runs, kept in its own cache: the worker may be stopped between events.
const PAGES = 'uv-exposure-pages';
const PAGES_KEY = 'pages.json';

const inScope = (path) => new URL(path, self.registration.scope).href;

self.addEventListener('install', (event) => {
  // cache: 'reload': a deploy minutes after a visit must not take the old index.html (or anything
  // else) from the HTTP cache, where it stays fresh for max-age.
  event.waitUntil(caches.open(CACHE).then((cache) => cache.addAll(PRECACHE.map((f) => new Request(inScope(f), { cache: 'reload' })))));
  // A first install takes over at once. An update waits: the page says "a new version is ready" and
  // lets it take over when no job runs (app/src/pwa-update.svelte.ts).
});

self.addEventListener('message', (event) => {
  const m = event.data;
  if (m?.type === 'skip-waiting') void self.skipWaiting();
  // A page tells which version it runs by its entry script: the cache that holds it is that version.
  else if (m?.type === 'running' && typeof m.entry === 'string' && event.source?.id) event.waitUntil(remember(event.source.id, m.entry));
});

self.addEventListener('activate', (event) => {
  event.waitUntil(self.clients.claim().then(prune));
});

// Read-modify-write of the pages' versions, one at a time.
let pagesQueue = Promise.resolve();
function updatePages(change) {
  const run = pagesQueue.then(async () => {
    const cache = await caches.open(PAGES);
    const hit = await cache.match(PAGES_KEY);
    const pages = hit ? await hit.json() : {};
    await change(pages);
    await cache.put(PAGES_KEY, new Response(JSON.stringify(pages), { headers: { 'content-type': 'application/json' } }));
  });
  pagesQueue = run.catch(() => {});
  return run;
}

async function remember(clientId, entry) {
  // This version first: a deploy that left the entry chunk as it was has it in both caches.
  for (const name of [CACHE, ...(await caches.keys()).reverse()]) {
    if (!name.startsWith(PREFIX) || name === PAGES) continue;
    if (await (await caches.open(name)).match(entry)) {
      await updatePages((pages) => void (pages[clientId] = name));
      return prune();
    }
  }
}

/**
 * Drops the caches of versions no open page runs. A page whose version is not known yet (loaded from
 * the network, before it said which) keeps every cache: a chunk it has not loaded may come from any.
 */
function prune() {
  return updatePages(async (pages) => {
    const open = await self.clients.matchAll({ type: 'window', includeUncontrolled: true });
    const kept = new Set([CACHE]);
    let unknown = false;
    for (const id of Object.keys(pages)) if (!open.some((c) => c.id === id)) delete pages[id];
    for (const c of open) {
      if (pages[c.id]) kept.add(pages[c.id]);
      else unknown = true;
    }
    if (unknown) return;
    for (const name of await caches.keys()) if (name.startsWith(PREFIX) && name !== PAGES && !kept.has(name)) await caches.delete(name);
  });
}

self.addEventListener('fetch', (event) => {
  const request = event.request;
  const url = new URL(request.url);
  if (request.method !== 'GET' || url.origin !== location.origin) return;
  const path = url.origin + url.pathname;
  // A page load of the app, with or without a query (?simSpeed=…): this version's shell.
  if (request.mode === 'navigate' && (path === inScope('./') || path === inScope('index.html'))) {
    event.respondWith(
      caches
        .open(CACHE)
        .then((cache) => cache.match(inScope('index.html')))
        .then((hit) => {
          if (!hit) return fetch(request);
          if (event.resultingClientId) event.waitUntil(updatePages((pages) => void (pages[event.resultingClientId] = CACHE)));
          return hit;
        }),
    );
    return;
  }
  // The app's files, this version's or an older one's that an open page still runs.
  if (!PRECACHE.some((f) => inScope(f) === path) && !path.startsWith(inScope('assets/'))) return; // the printer's API: the network
  event.respondWith(caches.match(path).then((hit) => hit ?? fetch(request)));
});
