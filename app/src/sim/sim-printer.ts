// The simulated printer's Mega: the dialect over a byte stream, backed by a simple thermal model.
// Runs in a Web Worker (the app's default device) and in Node (tests, desktop hosts).

import { parseCommand } from '../protocol/dialect-command';
import { LineReceiver } from '../protocol/dialect-receiver';
import { formatReply } from '../protocol/dialect-reply';
import { DIALECT_MAX_LINE } from '../protocol/dialect-frame';
import { ERRORS, errorByCode } from '../protocol/errors';
import { LineSplitter } from '../protocol/line-splitter';
import { SENSOR_COUNT } from '../protocol/nano';

export interface SimOptions {
  firmwareName?: string;
  /** Resting temperature of each sensor, tenths of °C. */
  ambientDeciC?: number[];
  limitDeciC?: number[];
  /** A slow ±0.3 °C drift on the temperatures (default on); tests turn it off for exact values. */
  drift?: boolean;
}

const WINDOW = 8;

export class SimPrinter {
  readonly #splitter = new LineSplitter(DIALECT_MAX_LINE);
  readonly #receiver: LineReceiver;
  readonly #name: string;
  readonly #ambient: number[];
  readonly #limits: number[];
  readonly #drift: boolean;
  #tempReportMs = 0;
  #lastTempReport = 0;
  #now = 0;

  /** `emit` receives every byte the Mega would send. */
  constructor(private readonly emit: (bytes: string) => void, options: SimOptions = {}) {
    this.#name = options.firmwareName ?? 'UVExposure 0.1.0 (Simulated Mega)';
    this.#ambient = options.ambientDeciC ?? [231, 234, 229, 236, 224, 226];
    this.#limits = options.limitDeciC ?? [600, 600, 600, 600, 550, 550];
    this.#drift = options.drift ?? true;
    this.#receiver = new LineReceiver({ movesFree: () => 8, windowFree: () => WINDOW });
  }

  /** Call once the port is open: a real Mega prints `start` after reset. */
  boot(): void {
    this.#line('start');
  }

  /** Bytes from the host. */
  receive(bytes: string): void {
    for (const line of this.#splitter.push(bytes)) {
      const a = this.#receiver.accept(line);
      if (a.kind === 'reply') a.lines.forEach((l) => this.#line(l));
      else if (a.kind === 'execute') this.#execute(a.body);
    }
  }

  /** Advances the simulated clock (ms); sends due auto-reports. */
  tick(nowMs: number): void {
    this.#now = nowMs;
    if (this.#tempReportMs > 0 && nowMs - this.#lastTempReport >= this.#tempReportMs) {
      this.#lastTempReport = nowMs;
      this.#line(this.#temps());
    }
  }

  #line(text: string): void {
    this.emit(text + '\n');
  }

  #ok(): void {
    this.#line(this.#receiver.ok());
  }

  #error(code: number, detail?: string): void {
    const message = errorByCode(code)!.message;
    this.#line(`Error:E${code} ${message}${detail ? `: ${detail}` : ''}`);
    this.#ok();
  }

  #temps(): string {
    // A small, slow drift so a chart of the simulated printer is not a flat line.
    const t = this.#now / 1000;
    const deciC = this.#ambient.map((a, i) => a + (this.#drift ? Math.round(3 * Math.sin(t / 7 + i)) : 0));
    return formatReply({ kind: 'temps', deciC, limitDeciC: this.#limits.slice(0, SENSOR_COUNT) });
  }

  #execute(body: string): void {
    const parsed = parseCommand(body);
    if (!parsed.ok) return this.#error(parsed.error, parsed.error === 10 ? body.split(' ')[0] : undefined);
    const { command } = parsed;
    const params = 'params' in command ? command.params : {};
    switch (command.word) {
      case 'M115':
        this.#line(formatReply({ kind: 'firmware', name: this.#name, protocol: 1 }));
        this.#line(`Cap:RX_WINDOW:${WINDOW}`);
        this.#line('Cap:AUTOREPORT_TEMP:1');
        return this.#ok();
      case 'M105':
        this.#line(this.#temps());
        return this.#ok();
      case 'M155': {
        const s = params.S;
        if (typeof s !== 'number' || s < 0 || s > 60000) return this.#error(ERRORS.bad_parameter.code);
        this.#tempReportMs = s;
        this.#lastTempReport = this.#now;
        return this.#ok();
      }
      default:
        return this.#error(ERRORS.unknown_command.code, command.word);
    }
  }
}
