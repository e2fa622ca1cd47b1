// The link to each kind of printer. The simulated printer's, which the app opens on start, is in the
// first load; the Wi-Fi hub's and USB's load when first chosen (a failed load is a failed connect).

import { DialectLink } from './dialect-link';
import type { PrinterLink } from './link';
import { SimTransport, switchOffSimulatedPrinter } from './sim-transport';
import type { TransportKind } from './transport';

export async function linkFor(kind: TransportKind): Promise<PrinterLink> {
  if (kind !== 'sim') switchOffSimulatedPrinter();
  if (kind === 'esp') return (await import('./chosen-links')).espLink();
  if (kind === 'serial') return (await import('./chosen-links')).serialLink();
  return new DialectLink(new SimTransport());
}
