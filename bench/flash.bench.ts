// F1: flashing from the browser's code (app/src/firmware) into the real bootloaders in simavr
// (build/host/bootloader_rig, paced to the wall clock, the boards' fuses modelled), without the browser:
// how long the reset, writing and reading back the Nano's and the Mega's images take, against the wire
// time of the image's bytes at the bootloader's baud (10 bits a byte, 8N1), and against Debian's avrdude
// flashing and verifying the same image through the same rig (scripts/avrdude-referee.py --times, over
// a pty). What stands above 1x of wire: the protocol's replies and page framing, each page's 4.5 ms
// erase and write, reading back, and a round trip per command through a pipe.
// F2: the ESP's check by MD5 against reading its largest region back (no ESP runs here: wire time).
import { execFileSync, spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { ByteQueue, type ByteLink } from '../app/src/firmware/byte-link';
import { AVR_BOARDS, type AvrBoardId } from '../app/src/firmware/chips';
import { ESP_LAYOUT } from '../app/src/firmware/esp-layout';
import { md5Hex } from '../app/src/firmware/md5';
import { flashAvr } from '../app/src/firmware/flash-avr';
import { parseIntelHex } from '../app/src/firmware/intel-hex';
import { RESET_SETTLE_MS } from '../app/src/firmware/serial-link';
import { BOOTLOADERS, IMAGES, buildRig } from '../e2e/bootloader-rig';

const RIG = new URL('../build/host/bootloader_rig', import.meta.url).pathname;

/** A ByteLink over the rig's stdio, as e2e/bootloader-rig.ts frames it. */
function rigLink(bootloader: keyof typeof BOOTLOADERS, baud: number): ByteLink & { stop(): void } {
  const b = BOOTLOADERS[bootloader];
  const child = spawn(RIG, ['--board', b.board, '--boot', b.hex], { stdio: ['pipe', 'pipe', 'inherit'] });
  const queue = new ByteQueue();
  child.stdout.on('data', (d: Buffer) => queue.push(new Uint8Array(d)));
  const baudFrame = Buffer.alloc(5);
  baudFrame.write('B', 0, 'latin1');
  baudFrame.writeUInt32LE(baud, 1);
  return {
    async write(bytes) {
      for (let at = 0; at < bytes.length; at += 255) {
        const part = bytes.subarray(at, at + 255);
        child.stdin.write(Buffer.concat([Buffer.from([0x44, part.length]), part]));
      }
    },
    read: (n, ms) => queue.read(n, ms),
    discard: () => queue.discard(),
    async reset() {
      child.stdin.write(baudFrame);
      child.stdin.write('R');
      await new Promise((r) => setTimeout(r, RESET_SETTLE_MS));
      queue.discard();
    },
    stop: () => child.kill(),
  };
}

/** avrdude's seconds per board, each through its own fresh rig (the referee's timing run). */
function avrdudeTimes(): Record<string, number> {
  const out = execFileSync('python3', ['scripts/avrdude-referee.py', '--times'], { cwd: new URL('..', import.meta.url).pathname, encoding: 'utf8' });
  return JSON.parse(out.trim().split('\n').at(-1)!);
}

export async function flashBench(): Promise<void> {
  buildRig();
  console.log('\nF1 flashing in simavr (real bootloaders and fuses, paced to the wall clock): the app against wire time and against avrdude through the same rig');
  const avrdude = avrdudeTimes();
  const cases: [AvrBoardId, keyof typeof BOOTLOADERS, string][] = [['nano', 'optiboot', IMAGES.nano], ['nano-old', 'atmegaboot', IMAGES.nano], ['mega', 'stk500v2', IMAGES.mega]];
  for (const [id, bootloader, file] of cases) {
    const board = AVR_BOARDS.find((x) => x.id === id)!;
    const { bytes } = parseIntelHex(readFileSync(file, 'utf8'));
    const link = rigLink(bootloader, board.baud);
    await new Promise((r) => setTimeout(r, 300)); // the rig's start, as the referee's avrdude has it before opening
    const wireS = (bytes.length * 10) / board.baud;
    const t0 = performance.now();
    await link.reset!(); // counted: avrdude's time includes its own reset and wait
    let wroteAt = 0;
    await flashAvr(link, board, bytes, (p) => {
      if (p.phase === 'writing' && p.done === p.total) wroteAt = performance.now();
    });
    const end = performance.now();
    link.stop();
    const [all, write, verify] = [(end - t0) / 1000, (wroteAt - t0) / 1000, (end - wroteAt) / 1000];
    console.log(
      `  ${board.name.padEnd(34)} ${String(bytes.length).padStart(6)} B at ${board.baud}: wire ${wireS.toFixed(2)} s;` +
        ` reset, synced and written ${write.toFixed(2)} s (${(write / wireS).toFixed(2)}x), read back ${verify.toFixed(2)} s (${(verify / wireS).toFixed(2)}x), in all ${all.toFixed(2)} s (${(all / wireS).toFixed(2)}x);` +
        ` avrdude ${avrdude[id].toFixed(2)} s: app/avrdude ${(all / avrdude[id]).toFixed(2)}x`,
    );
  }
  espVerifyBench();
}

/**
 * F2: the ESP8266's LittleFS region, which `pio run -t buildfs` fills whole: read back (esptool-js's
 * readFlash, 10 bits a byte at 460800 baud before SLIP's escapes and acknowledgements) against the
 * MD5 check (one SPI_FLASH_MD5 command and its answer, and the app's MD5 of the file, timed here).
 */
function espVerifyBench(): void {
  const region = ESP_LAYOUT.esp8266.find((r) => r.kind === 'littlefs')!;
  const image = Uint8Array.from({ length: region.size }, (_, i) => (i * 2654435761) >>> 24);
  const baud = 460800;
  const readBackS = (region.size * 10) / baud;
  const t0 = performance.now();
  md5Hex(image);
  const md5S = (performance.now() - t0) / 1000;
  // SLIP frames: the command's 8-byte header and 16-byte body, the answer's header, 32 hex digits and status.
  const md5WireS = ((2 + 8 + 16 + 2 + 8 + 32 + 2) * 10) / baud;
  console.log(
    `\nF2 ESP verify, ESP8266 LittleFS region ${region.size} B: read back >= ${readBackS.toFixed(1)} s of wire at ${baud};` +
      ` by MD5 ${(md5WireS * 1000).toFixed(1)} ms of wire + the app's MD5 ${(md5S * 1000).toFixed(0)} ms (the ESP's own MD5 of its flash is not timed: no ESP here)`,
  );
}

if (import.meta.url === `file://${process.argv[1]}`) await flashBench();
