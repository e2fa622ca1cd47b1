// The simulated printer's link: the Mega's text dialect over the simulator's worker. Loaded when the
// app connects to it, after the first screen is drawn (links.ts).

import { DialectLink } from './dialect-link';
import type { PrinterLink } from './link';
import { SimTransport } from './sim-transport';

export const simLink = (): PrinterLink => new DialectLink(new SimTransport());
