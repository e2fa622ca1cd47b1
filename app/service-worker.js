// The app's service worker: the app's own files come from the cache, so it starts with no network
// at all (the printer's access point has no internet, and a laptop on the bench may have none).
// The printer's API (/status, /print, /ws, /wifi) always goes to the network. The build fills in
// PRECACHE, the app's files, and VERSION, a hash of them: a new build installs a new cache.
const PRECACHE = self.__PRECACHE__;
const VERSION = self.__VERSION__;
const CACHE = `uv-exposure-${VERSION}`;

self.addEventListener('install', (event) => {
  event.waitUntil(caches.open(CACHE).then((cache) => cache.addAll(PRECACHE)).then(() => self.skipWaiting()));
});

self.addEventListener('activate', (event) => {
  event.waitUntil(
    caches
      .keys()
      .then((keys) => Promise.all(keys.filter((k) => k.startsWith('uv-exposure-') && k !== CACHE).map((k) => caches.delete(k))))
      .then(() => self.clients.claim()),
  );
});

self.addEventListener('fetch', (event) => {
  const url = new URL(event.request.url);
  if (event.request.method !== 'GET' || url.origin !== location.origin) return;
  // A page load of the app, with or without a query (?simSpeed=…): the cached shell.
  if (event.request.mode === 'navigate' && (url.pathname === '/' || url.pathname === '/index.html')) {
    event.respondWith(caches.match('/index.html').then((hit) => hit ?? fetch(event.request)));
    return;
  }
  if (!PRECACHE.includes(url.pathname)) return; // the printer's API and anything else: the network
  event.respondWith(caches.match(url.pathname).then((hit) => hit ?? fetch(event.request)));
});
