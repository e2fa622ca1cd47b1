// Web Worker host of the simulated printer: bytes in and out by postMessage, real time as its clock.

import { SimPrinter } from './sim-printer';

const printer = new SimPrinter((bytes) => postMessage({ type: 'rx', bytes }));
const start = performance.now();

onmessage = (e: MessageEvent<{ type: 'tx'; bytes: string }>) => {
  if (e.data.type === 'tx') printer.receive(e.data.bytes);
};

setInterval(() => printer.tick(performance.now() - start), 50);
printer.boot();
