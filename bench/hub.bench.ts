// P12: how soon the hub answers, on the ESP's core run on the host (build/host/esp_host) at real
// time, in loop passes (one pass of the hub's loop() is the unit: the host hub runs one every
// millisecond of its time, and says how many it ran). A GET /status answer, and the WebSocket
// relay (a `ping` through the inbox, loop() and the live channel to its `pong`). Three ways of
// giving the network side its turn: after each pass (the ESP8266); answers only at AsyncTCP's
// 500 ms poll, with the live channel sent from loop() (the ESP32 before issue 36, on the wrong
// task); and both on the network task, at that poll or when loop() wakes it (the ESP32 now).
import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import { request } from 'node:http';
import { connect, type Socket } from 'node:net';
import { join } from 'node:path';

const ROOT = join(import.meta.dirname, '..');
const BINARY = join(ROOT, 'build', 'host', 'esp_host');
const ROUNDS = 30;

interface Hub {
  url: string;
  stop(): Promise<number>; // the real milliseconds one loop pass took
}

function startHub(args: string[]): Promise<Hub> {
  const child = spawn(BINARY, ['--port', '0', '--www', join(ROOT, 'firmware', 'esp', 'data', 'www'), '--speed', '1', ...args], { stdio: ['pipe', 'pipe', 'inherit'] });
  let out = '';
  child.stdout.on('data', (d: Buffer) => (out += d.toString()));
  return new Promise((resolve) => {
    const check = setInterval(() => {
      const m = /listening on (http:\/\/\S+)/.exec(out);
      if (!m) return;
      clearInterval(check);
      resolve({
        url: m[1],
        stop: () =>
          new Promise((done) => {
            child.on('exit', () => {
              const p = /loop passes: (\d+) in (\d+) ms/.exec(out);
              done(p ? Number(p[2]) / Number(p[1]) : NaN);
            });
            child.stdin.end(); // the hub leaves when its stdin closes, and says how many passes it ran
          }),
      });
    }, 20);
  });
}

function getStatus(url: string): Promise<{ ms: number; body: string }> {
  const t0 = performance.now();
  return new Promise((resolve, reject) => {
    const r = request(new URL('/status', url), (res) => {
      let body = '';
      res.on('data', (d: Buffer) => (body += d.toString()));
      res.on('end', () => resolve({ ms: performance.now() - t0, body }));
    });
    r.on('error', reject);
    r.end();
  });
}

// A WebSocket client small enough to time: masked text frames out, the server's frames in.
class Ws {
  #socket: Socket;
  #buf = Buffer.alloc(0);
  #waiting: ((text: string) => void)[] = [];
  #frames: string[] = []; // come before anyone waits for them
  #handshook = false;
  constructor(url: string, opened: () => void) {
    const { port } = new URL(url);
    this.#socket = connect(Number(port), '127.0.0.1', () =>
      this.#socket.write(`GET /ws HTTP/1.1\r\nHost: 127.0.0.1:${port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n`),
    );
    this.#socket.on('data', (d: Buffer) => {
      this.#buf = Buffer.concat([this.#buf, d]);
      if (!this.#handshook) {
        const end = this.#buf.indexOf('\r\n\r\n');
        if (end < 0) return;
        this.#buf = this.#buf.subarray(end + 4);
        this.#handshook = true;
        opened();
      }
      for (;;) {
        if (this.#buf.length < 2) return;
        let len = this.#buf[1] & 0x7f;
        let at = 2;
        if (len === 126) (len = this.#buf.readUInt16BE(2)), (at = 4);
        if (this.#buf.length < at + len) return;
        const text = this.#buf.subarray(at, at + len).toString();
        this.#buf = this.#buf.subarray(at + len);
        const waiter = this.#waiting.shift();
        if (waiter) waiter(text);
        else this.#frames.push(text);
      }
    });
  }
  send(text: string): void {
    const payload = Buffer.from(text);
    const mask = Buffer.from([1, 2, 3, 4]);
    const frame = Buffer.concat([Buffer.from([0x81, 0x80 | payload.length]), mask, Buffer.from(payload.map((b, i) => b ^ mask[i % 4]))]);
    this.#socket.write(frame);
  }
  next(): Promise<string> {
    const early = this.#frames.shift();
    return early !== undefined ? Promise.resolve(early) : new Promise((resolve) => this.#waiting.push(resolve));
  }
  close(): void {
    this.#socket.destroy();
  }
}

async function until(text: (m: string) => boolean, ws: Ws): Promise<void> {
  while (!text(await ws.next()));
}

const median = (xs: number[]) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

async function measure(args: string[]): Promise<{ status: number; relay: number; passMs: number }> {
  const hub = await startHub(args);
  for (let i = 0; i < 100 && !JSON.parse((await getStatus(hub.url)).body).mega?.startsWith('online'); i++) await new Promise((r) => setTimeout(r, 100));
  const status: number[] = [];
  for (let i = 0; i < ROUNDS; i++) status.push((await getStatus(hub.url)).ms);
  const ws = await new Promise<Ws>((resolve) => {
    const w: Ws = new Ws(hub.url, () => resolve(w));
  });
  await until((m) => m.includes('"status"'), ws); // hello, then the first status
  const relay: number[] = [];
  for (let i = 0; i < ROUNDS; i++) {
    const t0 = performance.now();
    ws.send('{"type":"ping"}');
    await until((m) => m.includes('"pong"'), ws);
    relay.push(performance.now() - t0);
  }
  ws.close();
  const passMs = await hub.stop();
  return { status: median(status), relay: median(relay), passMs };
}

export async function hubLatency(): Promise<void> {
  if (!existsSync(BINARY)) throw new Error('build the host hub first: cmake --build build/host --target esp_host');
  console.log('\nP12 the hub on the host: answer latency in loop passes (median of ' + ROUNDS + '; ratio = latency / one loop pass)');
  for (const [name, args] of [
    ['ESP8266: sent after each pass', ['--board', 'esp8266', '--turn', 'each-pass']],
    ['ESP32 before: answers at the 500 ms poll', ['--board', 'esp32', '--turn', 'poll']],
    ['ESP32 now: the poll, or woken by loop()', ['--board', 'esp32', '--turn', 'wake']],
  ] as const) {
    const r = await measure([...args]);
    console.log(
      `  ${name.padEnd(42)} GET /status ${r.status.toFixed(1).padStart(6)} ms ${(r.status / r.passMs).toFixed(1).padStart(7)}x   ws ping→pong ${r.relay.toFixed(1).padStart(6)} ms ${(r.relay / r.passMs).toFixed(1).padStart(7)}x   (a pass ${r.passMs.toFixed(3)} ms)`,
    );
  }
}

