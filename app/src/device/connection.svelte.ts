// The app's one view of the printer: connection lifecycle as a discriminated union, plus the device state.

import { CommandError, PrinterClient, type DeviceReport } from './printer-client';
import { PickerDismissed, SerialTransport } from './serial-transport';
import { SimTransport } from './sim-transport';
import type { Transport, TransportKind } from './transport';

export type Connection =
  | { state: 'idle' }
  | { state: 'connecting'; kind: TransportKind }
  | { state: 'connected'; kind: TransportKind }
  | { state: 'lost'; kind: TransportKind; error: string }
  | { state: 'error'; kind: TransportKind; error: string };

export const SENSOR_NAMES = ['LED 0', 'LED 1', 'LED 2', 'LED 3', 'Driver', 'Frame'];

export class Printer {
  connection = $state<Connection>({ state: 'idle' });
  firmware = $state<string | null>(null);
  deciC = $state<number[] | null>(null);
  limitDeciC = $state<number[] | null>(null);
  #client: PrinterClient | null = null;

  constructor(private readonly makeTransport: (kind: TransportKind) => Transport = defaultTransport) {}

  async connect(kind: TransportKind): Promise<void> {
    await this.disconnect();
    this.connection = { state: 'connecting', kind };
    const client = new PrinterClient(this.makeTransport(kind), (r) => this.#report(r));
    this.#client = client;
    try {
      await client.open((error) => {
        if (this.#client !== client) return;
        this.#client = null;
        this.connection = { state: 'lost', kind, error: error?.message ?? 'link closed' };
      });
      await client.command('M115');
      await client.command('M105');
      await client.command('M155 S1');
      if (this.#client === client) this.connection = { state: 'connected', kind };
    } catch (e) {
      if (this.#client !== client) return;
      this.#client = null;
      if (e instanceof PickerDismissed) {
        this.connection = { state: 'idle' };
        return;
      }
      const message = e instanceof CommandError ? `E${e.code} ${e.message}` : (e as Error).message;
      this.connection = { state: 'error', kind, error: message };
      await client.close().catch(() => {});
    }
  }

  async disconnect(): Promise<void> {
    const client = this.#client;
    this.#client = null;
    this.firmware = null;
    this.deciC = null;
    this.limitDeciC = null;
    if (client) await client.close();
    this.connection = { state: 'idle' };
  }

  #report(r: DeviceReport): void {
    if (r.firmware) this.firmware = r.firmware;
    if (r.deciC) this.deciC = r.deciC;
    if (r.limitDeciC) this.limitDeciC = r.limitDeciC;
  }
}

function defaultTransport(kind: TransportKind): Transport {
  return kind === 'serial' ? new SerialTransport() : new SimTransport();
}
