// One byte-stream interface for every way the app reaches a printer (simulated, Web Serial, ESP).

export type TransportKind = 'sim' | 'serial' | 'esp';

export interface Transport {
  readonly kind: TransportKind;
  /** Printer seconds per wall second: 1 for a real machine; the simulated printer may run faster. */
  readonly timeScale?: number;
  /** Called when `timeScale` changes while the link is open (the simulated printer's panel sets its speed live). */
  onRescaled?: (() => void) | null;
  /** Opens the link; `onBytes` gets everything the printer sends, `onClosed` fires once if the link drops. */
  open(onBytes: (bytes: string) => void, onClosed: (error?: Error) => void): Promise<void>;
  send(bytes: string): Promise<void>;
  close(): Promise<void>;
}
