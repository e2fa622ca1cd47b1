import { p1 } from './link.bench';
const t = setTimeout(() => console.log('still pending'), 1e9);
await p1();
clearTimeout(t);
