// The link to each kind of printer, loaded when it is connected (a failed load is a failed connect):
// the simulated printer's with the text dialect's client, which the app opens just after the first
// screen, and the Wi-Fi hub's and USB's when first chosen.

import type { PrinterLink } from './link';
import { switchOffSimulatedPrinter } from './sim-transport';
import type { TransportKind } from './transport';

export async function linkFor(kind: TransportKind): Promise<PrinterLink> {
  if (kind !== 'sim') switchOffSimulatedPrinter();
  if (kind === 'esp') return (await import('./chosen-links')).espLink();
  if (kind === 'serial') return (await import('./chosen-links')).serialLink();
  return (await import('./sim-link')).simLink();
}
