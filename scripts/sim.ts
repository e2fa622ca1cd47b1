// npm run sim -- [--tcp PORT] [--pty] [--speed N]: the simulated printer as a serial device for desktop hosts
// (printrun, Pronterface, OctoPrint). TCP listens on 127.0.0.1; --pty bridges a pseudo-terminal with socat.
import { spawn, type ChildProcess } from 'node:child_process';
import net from 'node:net';
import { SimPrinter } from '../app/src/sim/sim-printer';

function arg(name: string): string | undefined {
  const i = process.argv.indexOf(name);
  return i >= 0 ? process.argv[i + 1] : undefined;
}

const pty = process.argv.includes('--pty');
const port = Number(arg('--tcp') ?? (pty ? 0 : 23100));
const speed = Number(arg('--speed') ?? 1);
let socket: net.Socket | null = null;

const printer = new SimPrinter((bytes) => socket?.write(Buffer.from(bytes, 'latin1')));
const start = Date.now();
setInterval(() => printer.tick((Date.now() - start) * speed), 10).unref?.();

const server = net.createServer((s) => {
  if (socket) {
    s.end('Error:E12 the simulated printer already has a host\n');
    return;
  }
  socket = s;
  s.setNoDelay(true);
  printer.boot(); // opening a port resets a real Mega
  s.on('data', (d) => printer.receive(d.toString('latin1')));
  s.on('close', () => (socket = null));
  s.on('error', () => (socket = null));
});

let socat: ChildProcess | null = null;
server.listen(port, '127.0.0.1', () => {
  const actual = (server.address() as net.AddressInfo).port;
  console.log(`simulated printer on tcp 127.0.0.1:${actual} (115200-baud Mega dialect, ${speed}x time)`);
  if (!pty) return;
  const link = `/tmp/uvsim-${process.pid}`;
  socat = spawn('socat', [`pty,raw,echo=0,link=${link}`, `tcp:127.0.0.1:${actual}`], { stdio: 'inherit' });
  socat.on('error', () => {
    console.error('--pty needs socat: apt-get install socat');
    process.exit(1);
  });
  console.log(`pty ${link}`);
});

const stop = () => {
  socat?.kill();
  server.close();
  process.exit(0);
};
process.on('SIGINT', stop);
process.on('SIGTERM', stop);
