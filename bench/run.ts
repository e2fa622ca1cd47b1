// npm run bench: every benchmark, printed as a table of medians and ratios to each group's baseline.
import { printTable } from './harness';
import { jobCodecBench } from './job-codec.bench';

printTable([...jobCodecBench()]);
