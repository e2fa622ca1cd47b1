// Writes protocol/vectors/planner-ts.json, scan-ts.json and mixed-ts.json: golden plans made by the TypeScript planners.
import { writeFileSync } from 'node:fs';
import { goldenCases } from '../app/src/planner/golden';
import { scanGoldenCases } from '../app/src/planner/scan-golden';
import { mixedGoldenCases } from '../app/src/planner/mixed-golden';

const cases = goldenCases();
writeFileSync(new URL('../protocol/vectors/planner-ts.json', import.meta.url), JSON.stringify({ version: 1, madeBy: 'typescript', cases }, null, 0) + '\n');
console.log(`wrote ${cases.length} cases`);
const scans = scanGoldenCases();
writeFileSync(new URL('../protocol/vectors/scan-ts.json', import.meta.url), JSON.stringify({ version: 1, madeBy: 'typescript', cases: scans }, null, 0) + '\n');
console.log(`wrote ${scans.length} scan cases`);
const mixed = mixedGoldenCases();
writeFileSync(new URL('../protocol/vectors/mixed-ts.json', import.meta.url), JSON.stringify({ version: 1, madeBy: 'typescript', cases: mixed }, null, 0) + '\n');
console.log(`wrote ${mixed.length} mixed cases`);
