// Web Worker host of the simulated printer: bytes in and out by postMessage, real time as its clock
// (times `speed`, which demos and tests may raise with ?simSpeed=N on the app's URL), and a power
// cycle each time the app opens its link again.

import { SimPrinter } from './sim-printer';

let speed = 1;
let start = performance.now();
const printer = new SimPrinter((bytes) => postMessage({ type: 'rx', bytes }));

onmessage = (e: MessageEvent<{ type: 'tx'; bytes: string } | { type: 'init'; speed: number } | { type: 'reset' }>) => {
  if (e.data.type === 'tx') printer.receive(e.data.bytes);
  else if (e.data.type === 'reset') printer.powerCycle(); // the link was opened again
  else if (e.data.type === 'init') {
    speed = Math.max(1, Math.min(1000, e.data.speed));
    start = performance.now() - printer.clock.now / 1000 / speed;
  }
};

setInterval(() => printer.tick((performance.now() - start) * speed), 20);
printer.boot();
