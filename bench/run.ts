// npm run bench: every benchmark, printed as tables of medians and ratios to each group's baseline.
import '../app/src/planner/wasm/node-planner-wasm'; // the app plans with the Mega's planner as WebAssembly: loaded first
import { printTable } from './harness';
import { jobCodecBench } from './job-codec.bench';
import { pcbBench } from './pcb.bench';
import { doseMapBench } from './dose-map.bench';
import { editorBench } from './editor.bench';
import { neverFreezeBench } from './never-freeze.bench';
import { flashBench } from './flash.bench';
import { hubLatency } from './hub.bench';
import { p1 } from './link.bench';
import { p13 } from './upload.bench';
import { p2, p7, printP2 } from './planner.bench';
import { p10, p10Planning, printP10, printP11 } from './scan.bench';
import { simSpeed } from './sim-speed.bench';

printTable([...jobCodecBench(), ...p7(), ...pcbBench(), ...doseMapBench()]);
printP2(p2());
printTable(p10Planning());
const scans = p10();
printP10(scans);
printP11(scans);
await p1();
await p13();
simSpeed();
await editorBench();
await neverFreezeBench();
await flashBench();
await hubLatency();
