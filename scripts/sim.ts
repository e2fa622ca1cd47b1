// npm run sim -- [--tcp PORT] [--pty] [--speed N] [--firmware]: the simulated printer as a serial device for
// desktop hosts (printrun, Pronterface, OctoPrint). TCP listens on 127.0.0.1; --pty bridges a pseudo-terminal
// with socat. --firmware runs the firmware's own C++ as WebAssembly (scripts/build-wasm.sh) instead of the
// TypeScript printer.
import { execFileSync, spawn, type ChildProcess } from 'node:child_process';
import { readFileSync } from 'node:fs';
import net from 'node:net';
import { SimPrinter } from '../app/src/sim/sim-printer';
import { FirmwareSerial } from '../app/src/sim/wasm/firmware-serial';
import { PrinterModule } from '../app/src/sim/wasm/printer-module';

function arg(name: string): string | undefined {
  const i = process.argv.indexOf(name);
  return i >= 0 ? process.argv[i + 1] : undefined;
}

const pty = process.argv.includes('--pty');
const port = Number(arg('--tcp') ?? (pty ? 0 : 23100));
const speed = Number(arg('--speed') ?? 1);
let socket: net.Socket | null = null;
let booted = false;

const toHost = (bytes: string) => socket?.write(Buffer.from(bytes, 'latin1'));
async function firmware(): Promise<FirmwareSerial> {
  execFileSync('bash', ['scripts/build-wasm.sh'], { stdio: ['ignore', 'ignore', 'inherit'] });
  return new FirmwareSerial(await PrinterModule.load(new Uint8Array(readFileSync('build/wasm/printer.wasm'))), toHost);
}
const printer = process.argv.includes('--firmware') ? await firmware() : new SimPrinter(toHost);
const start = Date.now();
setInterval(() => printer.tick((Date.now() - start) * speed), 10).unref?.();

/** A host opened the port: a real Mega resets when its USB port opens (DTR), so every new host finds it started afresh. */
function attach(s: net.Socket): void {
  socket = s;
  s.setNoDelay(true);
  if (booted) printer.resetMega();
  else printer.boot();
  booted = true;
  s.on('data', (d) => socket === s && printer.receive(d.toString('latin1')));
  const gone = () => {
    if (socket === s) socket = null;
  };
  s.on('end', gone); // the host closed its side: it is leaving, whatever the socket still flushes
  s.on('close', gone);
  s.on('error', gone);
}

/** Whether a connection is on its way out: closed, half-closed or failed. */
function leaving(s: net.Socket): boolean {
  return s.destroyed || s.readableEnded || !s.writable;
}

// One host at a time, as on a serial port. A newcomer takes over from a host that is gone or going; a
// probe that connects and closes at once may not have been seen closing yet, so the newcomer waits a
// moment for it before it is refused.
const TAKEOVER_WAIT_MS = 500;
const server = net.createServer((s) => {
  if (!socket || leaving(socket)) {
    socket?.destroy();
    return attach(s);
  }
  const old = socket;
  const refuse = setTimeout(() => {
    old.off('close', takeOver);
    s.end('Error:E12 the simulated printer already has a host\n');
  }, TAKEOVER_WAIT_MS);
  function takeOver(): void {
    clearTimeout(refuse);
    if (!s.destroyed) attach(s);
  }
  old.once('close', takeOver);
  old.once('end', () => old.destroy());
});

let socat: ChildProcess | null = null;
let stopping = false;

/**
 * --pty: socat makes a pseudo-terminal and, once a host opens it (wait-slave), connects it to the TCP
 * port; when the host closes it, socat ends and a new one waits for the next host. So opening the pty
 * opens a new connection, and resets the Mega, as opening a real one's USB port does.
 */
function serveThePty(link: string, tcpPort: number): void {
  socat = spawn('socat', [`pty,raw,echo=0,link=${link},wait-slave`, `tcp:127.0.0.1:${tcpPort}`], { stdio: 'inherit' });
  socat.on('error', () => {
    console.error('--pty needs socat: apt-get install socat');
    process.exit(1);
  });
  socat.on('exit', () => {
    if (!stopping) setTimeout(() => serveThePty(link, tcpPort), 50);
  });
}

server.listen(port, '127.0.0.1', () => {
  const actual = (server.address() as net.AddressInfo).port;
  const which = printer instanceof FirmwareSerial ? "the firmware's C++ as WebAssembly" : 'the TypeScript printer';
  console.log(`simulated printer on tcp 127.0.0.1:${actual} (115200-baud Mega dialect, ${speed}x time; ${which})`);
  if (!pty) return;
  const link = `/tmp/uvsim-${process.pid}`;
  serveThePty(link, actual);
  console.log(`pty ${link}`);
});

const stop = () => {
  stopping = true;
  socat?.kill();
  server.close();
  process.exit(0);
};
process.on('SIGINT', stop);
process.on('SIGTERM', stop);
