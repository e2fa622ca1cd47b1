// Test-only: a static server that answers as GitHub Pages does for a project site
// (https://OWNER.github.io/REPO/): the app under /uv-printer/, gzip when asked, Cache-Control
// max-age=600, an ETag and Last-Modified with 304s, a 404 page, /uv-printer redirected to
// /uv-printer/. deploy() swaps the served build at once, as a Pages deployment does, and
// cachedFor imitates time passed since a visit (an Age header, as Pages' CDN sends).
import { createHash } from 'node:crypto';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { createServer, type IncomingHttpHeaders } from 'node:http';
import type { AddressInfo } from 'node:net';
import { extname, join, normalize } from 'node:path';
import { gzipSync } from 'node:zlib';

export const BASE = '/uv-printer/';

const TYPES: Record<string, string> = {
  '.html': 'text/html; charset=utf-8', '.js': 'application/javascript; charset=utf-8', '.css': 'text/css; charset=utf-8',
  '.svg': 'image/svg+xml', '.webmanifest': 'application/manifest+json', '.json': 'application/json; charset=utf-8',
  '.wasm': 'application/wasm', '.bin': 'application/octet-stream', '.hex': 'application/octet-stream',
};
const NOT_FOUND = '<!DOCTYPE html><html><head><title>Page not found · GitHub Pages</title></head><body><h1>404</h1><p><strong>File not found</strong></p><p>The site configured at this address does not contain the requested file.</p></body></html>';

export interface PagesRequest {
  path: string;
  status: number;
  headers: IncomingHttpHeaders;
}

export interface PagesServer {
  /** http://127.0.0.1:PORT/uv-printer/ */
  url: string;
  /** Serves another build from now on, as a new deployment. */
  deploy(dir: string): void;
  /** Seconds each response is already old when it leaves (the Age header): a visit that long ago. */
  cachedFor: number;
  /** Every request, in order. */
  requests: PagesRequest[];
  close(): Promise<void>;
}

export async function startPagesServer(dir: string): Promise<PagesServer> {
  let root = dir;
  let deployed = new Date();
  const requests: PagesRequest[] = [];
  const state = { cachedFor: 0 };
  const server = createServer((req, res) => {
    const url = new URL(req.url ?? '/', 'http://localhost');
    const done = (status: number) => requests.push({ path: url.pathname, status, headers: req.headers });
    if (req.method !== 'GET' && req.method !== 'HEAD') {
      res.writeHead(405, { allow: 'GET, HEAD' }).end();
      return done(405);
    }
    if (url.pathname === BASE.slice(0, -1)) {
      res.writeHead(301, { location: BASE + url.search, 'cache-control': 'max-age=600' }).end();
      return done(301);
    }
    let file = '';
    if (url.pathname.startsWith(BASE)) {
      const rel = normalize(decodeURIComponent(url.pathname.slice(BASE.length)) || 'index.html');
      file = join(root, rel.endsWith('/') ? join(rel, 'index.html') : rel);
      if (!file.startsWith(root) || !existsSync(file) || statSync(file).isDirectory()) file = '';
    }
    const headers: Record<string, string> = {
      'cache-control': 'max-age=600',
      'access-control-allow-origin': '*',
      vary: 'Accept-Encoding',
      age: String(state.cachedFor),
    };
    if (!file) {
      res.writeHead(404, { ...headers, 'content-type': 'text/html; charset=utf-8' }).end(req.method === 'HEAD' ? undefined : NOT_FOUND);
      return done(404);
    }
    const body = readFileSync(file);
    const etag = `"${createHash('sha1').update(body).digest('hex').slice(0, 16)}"`;
    headers.etag = etag;
    headers['last-modified'] = deployed.toUTCString();
    headers['content-type'] = TYPES[extname(file)] ?? 'application/octet-stream';
    const since = req.headers['if-modified-since'];
    if (req.headers['if-none-match'] === etag || (!req.headers['if-none-match'] && since && Date.parse(since) >= Math.floor(deployed.getTime() / 1000) * 1000)) {
      res.writeHead(304, headers).end();
      return done(304);
    }
    let out = body;
    if (/\bgzip\b/.test(String(req.headers['accept-encoding'] ?? ''))) {
      out = gzipSync(body);
      headers['content-encoding'] = 'gzip';
    }
    headers['content-length'] = String(out.length);
    res.writeHead(200, headers).end(req.method === 'HEAD' ? undefined : out);
    done(200);
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address() as AddressInfo;
  return {
    url: `http://127.0.0.1:${port}${BASE}`,
    deploy(next: string) {
      root = next;
      deployed = new Date(Math.max(Date.now(), deployed.getTime() + 1000)); // Last-Modified moves on
    },
    get cachedFor() {
      return state.cachedFor;
    },
    set cachedFor(s: number) {
      state.cachedFor = s;
    },
    requests,
    close: () => new Promise<void>((resolve) => {
      server.closeAllConnections();
      server.close(() => resolve());
    }),
  };
}
