// Test-only: starts the ESP's hub built for the host (firmware/esp/host) on a free port, with the
// app's flash image (firmware/esp/data/www) and the simulated Mega running `speed` times real time.
import { execFileSync, spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join } from 'node:path';

const ROOT = join(import.meta.dirname, '..');
const BINARY = join(ROOT, 'build', 'host', 'esp_host');
export const WWW = join(ROOT, 'firmware', 'esp', 'data', 'www');

export interface EspHost {
  url: string;
  pid: number;
  /** The hub's own live heap (operator new), apart from the simulated Mega's (heap_count.h). */
  heap(): Promise<{ hubBytes: number; hubBlocks: number; rigBytes: number }>;
  stop(): void;
}

/** `args`: more of esp_host's options, e.g. a shorter request deadline. */
export async function startEspHost(speed: number, args: string[] = []): Promise<EspHost> {
  if (!existsSync(BINARY)) {
    execFileSync('cmake', ['-S', 'firmware', '-B', 'build/host'], { cwd: ROOT, stdio: 'ignore' });
    execFileSync('cmake', ['--build', 'build/host', '--target', 'esp_host', '-j4'], { cwd: ROOT, stdio: 'ignore' });
  }
  if (!existsSync(join(WWW, 'index.html.gz'))) execFileSync('node', ['scripts/build-esp-fs.mjs'], { cwd: ROOT, stdio: 'ignore' });
  // stdin is a pipe the hub watches: when this process goes, however it goes, so does the hub.
  const child = spawn(BINARY, ['--port', '0', '--www', WWW, '--speed', String(speed), ...args], { cwd: ROOT, stdio: ['pipe', 'pipe', 'inherit'] });
  const kill = () => child.kill();
  process.once('exit', kill);
  const url = await new Promise<string>((resolve, reject) => {
    let out = '';
    child.stdout.on('data', (d: Buffer) => {
      out += d.toString();
      const m = /listening on (http:\/\/\S+)/.exec(out);
      if (m) resolve(m[1]);
    });
    child.on('exit', (code) => reject(new Error(`esp_host exited with ${code}`)));
  });
  const heapWaiters: ((line: string) => void)[] = [];
  let lines = '';
  child.stdout.on('data', (d: Buffer) => {
    lines += d.toString();
    for (let nl = lines.indexOf('\n'); nl >= 0; nl = lines.indexOf('\n')) {
      const line = lines.slice(0, nl);
      lines = lines.slice(nl + 1);
      if (line.startsWith('heap:')) heapWaiters.shift()?.(line);
    }
  });
  return {
    url,
    pid: child.pid ?? 0,
    heap: () =>
      new Promise((resolve) => {
        heapWaiters.push((line) => {
          const m = /hub (\d+) B in (\d+) blocks, rig (\d+) B/.exec(line) ?? [];
          resolve({ hubBytes: Number(m[1]), hubBlocks: Number(m[2]), rigBytes: Number(m[3]) });
        });
        child.stdin.write('heap\n');
      }),
    stop: () => {
      process.off('exit', kill);
      child.kill();
    },
  };
}
