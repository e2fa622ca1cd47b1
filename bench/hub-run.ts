// P12 alone: npx tsx bench/hub-run.ts (npm run bench runs it with the others).
import { hubLatency } from './hub.bench';

await hubLatency();
