// Test-only: a board at the end of the fake USB cable whose chip runs its real bootloader in simavr
// (build/host/bootloader_rig, firmware/boot/bootloader_rig.cpp). Bytes, the port's baud and DTR pulses
// go to the rig on its stdin; the chip's bytes come back on its stdout.
import { execFileSync, spawn, type ChildProcess } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import type { FakeSerial, SerialPeer } from './fake-serial';

const ROOT = join(import.meta.dirname, '..');
const RIG = join(ROOT, 'build', 'host', 'bootloader_rig');
export const BOOTLOADERS = {
  optiboot: { board: 'nano', hex: join(ROOT, 'build', 'boot', 'optiboot_atmega328.hex') },
  atmegaboot: { board: 'nano', hex: join(ROOT, 'build', 'boot', 'atmegaboot_atmega328.hex') },
  stk500v2: { board: 'mega', hex: join(ROOT, 'build', 'boot', 'stk500v2_atmega2560.hex') },
} as const;
export const IMAGES = { nano: join(ROOT, 'build', 'avr', 'nano.hex'), mega: join(ROOT, 'build', 'avr', 'mega.hex') };

/** Builds what the rig needs when a checkout has not yet (npm test builds them in its earlier stages). */
export function buildRig(): void {
  if (!existsSync(IMAGES.nano) || !existsSync(IMAGES.mega)) execFileSync('bash', ['scripts/build-avr.sh'], { cwd: ROOT, stdio: 'ignore' });
  if (!existsSync(BOOTLOADERS.stk500v2.hex)) execFileSync('bash', ['scripts/build-bootloaders.sh'], { cwd: ROOT, stdio: 'ignore' });
  if (!existsSync(RIG)) {
    execFileSync('cmake', ['-S', 'firmware', '-B', 'build/host'], { cwd: ROOT, stdio: 'ignore' });
    execFileSync('cmake', ['--build', 'build/host', '--target', 'bootloader_rig', '-j1'], { cwd: ROOT, stdio: 'ignore' });
  }
}

export class SimulatedBoard implements SerialPeer {
  readonly #child: ChildProcess;
  #fake: FakeSerial | null = null;
  #dtr = true;
  /** Bytes the page has sent; `pullAfter` pulls the cable once this many have gone. */
  sent = 0;
  pullAfter = Infinity;
  #pulled = false;
  /** Everything the chip sent, as text. */
  heard = '';

  constructor(readonly bootloader: keyof typeof BOOTLOADERS, app?: string) {
    buildRig();
    const b = BOOTLOADERS[bootloader];
    const args = ['--board', b.board, '--boot', b.hex, ...(app ? ['--app', app] : [])];
    // stdin is the rig's lifeline: when this process goes, however it goes, so does the rig.
    this.#child = spawn(RIG, args, { stdio: ['pipe', 'pipe', 'inherit'] });
    this.#child.stdout!.on('data', (d: Buffer) => {
      const text = d.toString('latin1');
      this.heard += text;
      if (!this.#pulled) void this.#fake?.push(text);
    });
    process.once('exit', () => this.#child.kill());
  }

  /** What installFakeSerial calls: the cable's page end. */
  attach = (fake: FakeSerial): SerialPeer => {
    this.#fake = fake;
    return this;
  };

  /** The cable is plugged in again: the next port the page opens reaches the board. */
  plugIn(): void {
    this.#pulled = false;
    this.pullAfter = Infinity;
  }

  open(baud: number): void {
    const frame = Buffer.alloc(5);
    frame.write('B', 0, 'latin1');
    frame.writeUInt32LE(baud, 1);
    this.#child.stdin!.write(frame);
    this.#child.stdin!.write('R'); // opening the port asserts DTR: the board resets
  }

  signals(s: { dataTerminalReady?: boolean }): void {
    if (s.dataTerminalReady === undefined) return;
    if (s.dataTerminalReady && !this.#dtr) this.#child.stdin!.write('R');
    this.#dtr = s.dataTerminalReady;
  }

  receive(bytes: string): void {
    if (this.#pulled) return;
    let data = Buffer.from(bytes, 'latin1');
    if (this.sent + data.length >= this.pullAfter) {
      data = data.subarray(0, Math.max(0, this.pullAfter - this.sent));
      this.#pulled = true;
      void this.#fake?.lose();
    }
    this.sent += data.length;
    for (let at = 0; at < data.length; at += 255) {
      const part = data.subarray(at, at + 255);
      this.#child.stdin!.write(Buffer.concat([Buffer.from([0x44, part.length]), part]));
    }
  }

  /**
   * Whether the chip's bootloader still answers, asked from here after a reset as a second host would:
   * Optiboot its GET_SYNC, the Mega's bootloader its sign-on.
   */
  async bootloaderAnswers(): Promise<boolean> {
    const stk500v2 = this.bootloader === 'stk500v2';
    const ask = stk500v2 ? Buffer.from([0x1b, 0x01, 0x00, 0x01, 0x0e, 0x01, 0x14]) : Buffer.from([0x30, 0x20]);
    const answer = stk500v2 ? 'AVRISP_2' : '\x14\x10';
    this.#pulled = true; // the page's port hears none of this
    const from = this.heard.length;
    this.open(this.bootloader === 'atmegaboot' ? 57600 : 115200);
    for (let i = 0; i < 20; i++) {
      await new Promise((r) => setTimeout(r, 150));
      this.#child.stdin!.write(Buffer.concat([Buffer.from([0x44, ask.length]), ask]));
      if (this.heard.slice(from).includes(answer)) return true;
    }
    return false;
  }

  stop(): void {
    this.#child.kill();
  }
}
