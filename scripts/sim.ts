// npm run sim -- [--tcp PORT] [--pty] [--speed N]: the simulated printer (the firmware's own C++ as
// WebAssembly, app/src/sim/sim-printer.ts) as a serial device for desktop hosts (printrun, Pronterface,
// OctoPrint). TCP listens on 127.0.0.1; --pty bridges a pseudo-terminal with socat.
import { spawn, type ChildProcess } from 'node:child_process';
import net from 'node:net';
import '../app/src/sim/wasm/node-firmware';
import { SimPrinter } from '../app/src/sim/sim-printer';

function arg(name: string): string | undefined {
  const i = process.argv.indexOf(name);
  return i >= 0 ? process.argv[i + 1] : undefined;
}

const pty = process.argv.includes('--pty');
const port = Number(arg('--tcp') ?? (pty ? 0 : 23100));
const speed = Number(arg('--speed') ?? 1);
let socket: net.Socket | null = null;

const toHost = (bytes: string) => socket?.write(Buffer.from(bytes, 'latin1'));
const printer = new SimPrinter(toHost);
let start = Date.now();
// In slices of at most 40 ms of wall time: a machine slower than asked falls behind, its clock
// starting again from where it got, rather than hold up the host's bytes.
setInterval(() => {
  const began = Date.now();
  const target = (began - start) * speed;
  while (printer.clock.now / 1000 < target && Date.now() - began < 40) printer.tick(Math.min(target, printer.clock.now / 1000 + 20 * speed));
  if (printer.clock.now / 1000 < target) start = Date.now() - printer.clock.now / 1000 / speed;
}, 10).unref?.();

/** A host opened the port: a real Mega resets when its USB port opens (DTR), so every new host finds it started afresh. */
function attach(s: net.Socket): void {
  socket = s;
  s.setNoDelay(true);
  printer.boot(); // opening the port resets the Mega (DTR)
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
  console.log(`simulated printer on tcp 127.0.0.1:${actual} (the firmware's C++ as WebAssembly, 115200 baud, ${speed}x time)`);
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
