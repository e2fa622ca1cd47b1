// The links made only once the user picks their device, the Wi-Fi hub's and USB's: one chunk,
// loaded with the first of them (links.ts).

import { DialectLink } from './dialect-link';
import { EspLink } from './esp-link';
import type { PrinterLink } from './link';
import { SerialTransport } from './serial-transport';

export const espLink = (): PrinterLink => new EspLink(location.origin);

export const serialLink = (): PrinterLink => new DialectLink(new SerialTransport());
