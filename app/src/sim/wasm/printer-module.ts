// The machine's firmware cores as WebAssembly (firmware/wasm/printer_module.cpp, built by
// scripts/build-wasm.sh into printer.wasm beside this file): one instance of the module is one
// machine. This wraps its C ABI of bytes and time; the simulated printer (../sim-printer.ts) puts
// the physics around it.

/** The Mega's host ports: USB (the app, desktop hosts) and the ESP's UART. */
export type HostPort = 0 | 1;

interface Exports {
  memory: WebAssembly.Memory;
  _initialize(): void;
  printer_start(): void;
  printer_reset(powerLost: number): void;
  printer_inbox(n: number): number;
  printer_receive(port: number, n: number): void;
  printer_run(us: number): void;
  printer_sent(port: number): number;
  printer_outbox(): number;
  printer_position(axis: number): number;
  printer_on_us(led: number): number;
  printer_temps(): void;
  printer_nano_missing(missing: number): void;
  printer_probe_alarm(armed: number): void;
  printer_card_inserted(inserted: number): void;
  printer_card_count(): number;
  printer_card_name(i: number, n: number): number;
  printer_card_file(i: number, n: number): number;
  printer_card_put(nameLen: number): void;
  printer_card_revision(): number;
  printer_eeprom(): number;
  printer_eeprom_writes(): number;
  printer_starts(): number;
  printer_set_starts(n: number): void;
  printer_card_job(): number;
  printer_fires(): number;
  printer_lit(): number;
  printer_command(port: number): void;
  printer_display_row(r: number, n: number): number;
  printer_display_draws(): number;
  printer_display_frame(): number;
  printer_buttons(held: number): void;
}

/** What the module asks of its host: the bed's surface under the probe, µm of the head's Z. */
export interface ModuleWorld {
  bedUm(xUm: number, yUm: number): number;
}

export const EEPROM_BYTES = 4096;
export const SCREEN_ROWS = 8;
/** The SSD1306's memory: 128 columns × 8 pages of 8 pixels. */
export const DISPLAY_FRAME_BYTES = 1024;

/** The few WASI calls the C library links (stdio it never uses but for an abort's message): a
 *  message to stderr is kept for the error the trap raises, anything else is refused. */
function wasiStubs(memory: () => WebAssembly.Memory, stderr: string[]): WebAssembly.ModuleImports {
  const EBADF = 8;
  return {
    fd_write(fd: number, iovs: number, count: number, written: number): number {
      const view = new DataView(memory().buffer);
      let n = 0;
      for (let i = 0; i < count; i++) {
        const ptr = view.getUint32(iovs + i * 8, true);
        const len = view.getUint32(iovs + i * 8 + 4, true);
        if (fd === 2) stderr.push(new TextDecoder().decode(new Uint8Array(memory().buffer, ptr, len)));
        n += len;
      }
      view.setUint32(written, n, true);
      return fd === 1 || fd === 2 ? 0 : EBADF;
    },
    fd_close: () => EBADF,
    fd_seek: () => EBADF,
  };
}

/** Latin-1 both ways: the wire carries bytes, and a corrupted byte must pass as itself. */
const toBytes = (s: string) => Uint8Array.from(s, (c) => c.charCodeAt(0) & 0xff);
function fromBytes(b: Uint8Array): string {
  let s = '';
  for (let i = 0; i < b.length; i += 8192) s += String.fromCharCode(...b.subarray(i, i + 8192));
  return s;
}

export class PrinterModule {
  readonly #x: Exports;
  /** What the C library wrote to stderr, as an abort's reason. */
  readonly stderr: string[] = [];

  /** A machine from the compiled module; `world` answers what it asks of the physics outside it. */
  constructor(module: WebAssembly.Module, world: ModuleWorld = { bedUm: () => -1e9 }) {
    let memory: WebAssembly.Memory | null = null;
    const instance = new WebAssembly.Instance(module, {
      wasi_snapshot_preview1: wasiStubs(() => memory!, this.stderr),
      env: { bed_um: (x: number, y: number) => Math.round(world.bedUm(x, y)) | 0 },
    });
    this.#x = instance.exports as unknown as Exports;
    memory = this.#x.memory;
    this.#x._initialize();
  }

  /** Compiles the module's bytes (once per page or process; each machine is an instance). */
  static compile(bytes: BufferSource): Promise<WebAssembly.Module> {
    return WebAssembly.compile(bytes);
  }

  /** Power-up: a new machine with a blank card and EEPROM; it says `start` on both ports. */
  start(): void {
    this.#x.printer_start();
  }

  /** The Mega restarts (a host opened its USB port: the card and the EEPROM are kept), or with
   *  `powerLost` the whole machine does, the Nano's start count one more. */
  reset(powerLost = false): void {
    this.#x.printer_reset(powerLost ? 1 : 0);
  }

  #inbox(data: Uint8Array): void {
    const at = this.#x.printer_inbox(data.length);
    new Uint8Array(this.#x.memory.buffer, at, data.length).set(data);
  }

  /** Bytes on the wire to the Mega's port, at 115200 baud from now on. */
  receive(port: HostPort, bytes: Uint8Array | string): void {
    const data = typeof bytes === 'string' ? toBytes(bytes) : bytes;
    this.#inbox(data);
    this.#x.printer_receive(port, data.length);
  }

  /** A command line as a host would send it, numbered and framed by the module. */
  command(port: HostPort, body: string): void {
    this.#inbox(toBytes(body));
    this.#x.printer_command(port);
  }

  /** Runs the machine for `us` microseconds of its own time (whole 100 µs passes). */
  run(us: number): void {
    if (!Number.isInteger(us) || us < 0 || us > 0xffffffff) throw new RangeError(`run: ${us} µs is not a whole 32-bit count`);
    this.#x.printer_run(us);
  }

  /** What the Mega sent on a port since the last call: whole lines, each with its '\n'. */
  sentBytes(port: HostPort): string {
    const n = this.#x.printer_sent(port);
    return n ? fromBytes(new Uint8Array(this.#x.memory.buffer, this.#x.printer_outbox(), n)) : '';
  }

  /** The lines the Mega sent on a port since the last call. */
  sent(port: HostPort): string[] {
    return this.sentBytes(port).split('\n').slice(0, -1);
  }

  /** The head's place in steps, as the motors' pulses put it. */
  position(axis: 0 | 1 | 2): number {
    return this.#x.printer_position(axis);
  }

  /** How long each LED has shone since power-up, µs. */
  onUs(led: number): number {
    return this.#x.printer_on_us(led);
  }

  /** The six sensors read these temperatures (0.1 °C) from now on. */
  temps(deciC: readonly number[]): void {
    const b = new Int16Array(6);
    for (let i = 0; i < 6; i++) b[i] = Math.max(-32768, Math.min(32767, Math.round(deciC[i] ?? 0)));
    this.#inbox(new Uint8Array(b.buffer));
    this.#x.printer_temps();
  }

  nanoMissing(missing: boolean): void {
    this.#x.printer_nano_missing(missing ? 1 : 0);
  }

  probeAlarm(armed: boolean): void {
    this.#x.printer_probe_alarm(armed ? 1 : 0);
  }

  cardInserted(inserted: boolean): void {
    this.#x.printer_card_inserted(inserted ? 1 : 0);
  }

  #text(call: (lenAt: number) => number): string {
    const lenAt = this.#x.printer_inbox(4); // the length comes back through the inbox
    const at = call(lenAt);
    const n = new DataView(this.#x.memory.buffer).getUint32(lenAt, true);
    return fromBytes(new Uint8Array(this.#x.memory.buffer, at, n));
  }

  /** What the card durably holds, by name in its listing's order. */
  card(): [string, string][] {
    const files: [string, string][] = [];
    for (let i = 0, n = this.#x.printer_card_count(); i < n; i++) {
      files.push([this.#text((l) => this.#x.printer_card_name(i, l)), this.#text((l) => this.#x.printer_card_file(i, l))]);
    }
    return files;
  }

  /** Puts a file on the card as it was kept. */
  putFile(name: string, text: string): void {
    const n = toBytes(name);
    const data = new Uint8Array(n.length + text.length);
    data.set(n);
    data.set(toBytes(text), n.length);
    this.#inbox(data);
    this.#x.printer_card_put(n.length);
  }

  /** Counts every change of what the card durably holds. */
  get cardRevision(): number {
    return this.#x.printer_card_revision();
  }

  /** The Mega's EEPROM, a copy. */
  eeprom(): Uint8Array {
    return new Uint8Array(this.#x.memory.buffer, this.#x.printer_eeprom(), EEPROM_BYTES).slice();
  }

  setEeprom(bytes: Uint8Array): void {
    new Uint8Array(this.#x.memory.buffer, this.#x.printer_eeprom(), EEPROM_BYTES).set(bytes.subarray(0, EEPROM_BYTES));
  }

  get eepromWrites(): number {
    return this.#x.printer_eeprom_writes();
  }

  /** The Nano's start count. */
  get starts(): number {
    return this.#x.printer_starts();
  }

  set starts(n: number) {
    this.#x.printer_set_starts(n);
  }

  /** A job from the card is exposing now: null, or whether it runs paced. */
  cardJob(): { paced: boolean } | null {
    const j = this.#x.printer_card_job();
    return j ? { paced: j === 2 } : null;
  }

  /** Exposures the Nano has fired by F. */
  get fires(): number {
    return this.#x.printer_fires();
  }

  /** The LEDs lit now, a bit mask. */
  get lit(): number {
    return this.#x.printer_lit();
  }

  /** The Mega's OLED, row by row, as the firmware last wrote it. */
  display(): string[] {
    return Array.from({ length: SCREEN_ROWS }, (_, r) => this.#text((l) => this.#x.printer_display_row(r, l)));
  }

  /** The OLED's 128 × 64 pixels as the SSD1306 holds them: 8 pages of 128 columns, bit 0 the top. */
  displayFrame(): Uint8Array {
    return new Uint8Array(this.#x.memory.buffer, this.#x.printer_display_frame(), DISPLAY_FRAME_BYTES).slice();
  }

  get displayDraws(): number {
    return this.#x.printer_display_draws();
  }

  /** The panel's buttons held down, a bit mask. */
  buttons(held: number): void {
    this.#x.printer_buttons(held);
  }
}
