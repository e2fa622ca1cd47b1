// Writes protocol/vectors/planner-ts.json: golden plans made by the TypeScript planner.
import { writeFileSync } from 'node:fs';
import { goldenCases } from '../app/src/planner/golden';

const cases = goldenCases();
writeFileSync(new URL('../protocol/vectors/planner-ts.json', import.meta.url), JSON.stringify({ version: 1, madeBy: 'typescript', cases }, null, 0) + '\n');
console.log(`wrote ${cases.length} cases`);
