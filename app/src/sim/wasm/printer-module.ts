// The machine's firmware cores as WebAssembly (firmware/wasm/printer_module.cpp, built by
// scripts/build-wasm.sh): loads the module and wraps its C ABI of bytes and time. The first brick
// of the simulated printer that runs the firmware's own C++ (issue 27); nothing uses it yet but its test.

/** The Mega's host ports: USB (the app, desktop hosts) and the ESP's UART. */
export type HostPort = 0 | 1;

interface Exports {
  memory: WebAssembly.Memory;
  _initialize(): void;
  printer_start(): void;
  printer_reset(): void;
  printer_inbox(n: number): number;
  printer_receive(port: number, n: number): void;
  printer_run(us: number): void;
  printer_sent(port: number): number;
  printer_outbox(): number;
  printer_position(axis: number): number;
}

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

export class PrinterModule {
  readonly #x: Exports;
  /** What the C library wrote to stderr, as an abort's reason. */
  readonly stderr: string[];

  private constructor(instance: WebAssembly.Instance, stderr: string[]) {
    this.#x = instance.exports as unknown as Exports;
    this.stderr = stderr;
    this.#x._initialize();
  }

  static async load(bytes: BufferSource): Promise<PrinterModule> {
    const stderr: string[] = [];
    let memory: WebAssembly.Memory | null = null;
    const { instance } = await WebAssembly.instantiate(bytes, { wasi_snapshot_preview1: wasiStubs(() => memory!, stderr) });
    memory = instance.exports.memory as WebAssembly.Memory;
    return new PrinterModule(instance, stderr);
  }

  /** Power-up: a new machine with a blank card and EEPROM; it says `start` on both ports. */
  start(): void {
    this.#x.printer_start();
  }

  /** The Mega restarts (a host opened its USB port): the card and the EEPROM are kept. */
  reset(): void {
    this.#x.printer_reset();
  }

  /** Bytes on the wire to the Mega's port, at 115200 baud from now on. */
  receive(port: HostPort, bytes: Uint8Array | string): void {
    const data = typeof bytes === 'string' ? new TextEncoder().encode(bytes) : bytes;
    const at = this.#x.printer_inbox(data.length);
    new Uint8Array(this.#x.memory.buffer, at, data.length).set(data);
    this.#x.printer_receive(port, data.length);
  }

  /** Runs the machine for `us` microseconds of its own time. */
  run(us: number): void {
    if (!Number.isInteger(us) || us < 0 || us > 0xffffffff) throw new RangeError(`run: ${us} µs is not a whole 32-bit count`);
    this.#x.printer_run(us);
  }

  /** The lines the Mega sent on a port since the last call. */
  sent(port: HostPort): string[] {
    const n = this.#x.printer_sent(port);
    const text = new TextDecoder().decode(new Uint8Array(this.#x.memory.buffer, this.#x.printer_outbox(), n));
    return text.split('\n').slice(0, -1);
  }

  /** The head's place in steps, as the motors' pulses put it. */
  position(axis: 0 | 1 | 2): number {
    return this.#x.printer_position(axis);
  }
}
