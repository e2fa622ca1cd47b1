// P13 alone: npx tsx bench/upload-run.ts (npm run bench runs it with the others).
import { p13 } from './upload.bench';

await p13();
