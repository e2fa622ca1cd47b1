// F1: flashing from the browser's code (app/src/firmware) into the real bootloaders in simavr
// (build/host/bootloader_rig, paced to the wall clock), without the browser: how long writing and
// reading back the Nano's and the Mega's images take, against the wire time of the image's bytes at
// the bootloader's baud (10 bits a byte, 8N1). What stands above 1x: the protocol's replies and
// page framing, reading back, and a round trip per command through a pipe.
import { spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { ByteQueue, type ByteLink } from '../app/src/firmware/byte-link';
import { AVR_BOARDS, type AvrBoardId } from '../app/src/firmware/chips';
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

export async function flashBench(): Promise<void> {
  buildRig();
  console.log('\nF1 flashing in simavr (real bootloaders, paced to the wall clock): time / wire time of the image at the bootloader\'s baud');
  const cases: [AvrBoardId, keyof typeof BOOTLOADERS, string][] = [['nano', 'optiboot', IMAGES.nano], ['nano-old', 'atmegaboot', IMAGES.nano], ['mega', 'stk500v2', IMAGES.mega]];
  for (const [id, bootloader, file] of cases) {
    const board = AVR_BOARDS.find((x) => x.id === id)!;
    const { bytes } = parseIntelHex(readFileSync(file, 'utf8'));
    const link = rigLink(bootloader, board.baud);
    await link.reset!();
    const wireS = (bytes.length * 10) / board.baud;
    const t0 = performance.now();
    let wroteAt = 0;
    await flashAvr(link, board, bytes, (p) => {
      if (p.phase === 'writing' && p.done === p.total) wroteAt = performance.now();
    });
    const end = performance.now();
    link.stop();
    const [all, write, verify] = [(end - t0) / 1000, (wroteAt - t0) / 1000, (end - wroteAt) / 1000];
    console.log(
      `  ${board.name.padEnd(34)} ${String(bytes.length).padStart(6)} B at ${board.baud}: wire ${wireS.toFixed(2)} s;` +
        ` synced and written ${write.toFixed(2)} s (${(write / wireS).toFixed(2)}x), read back ${verify.toFixed(2)} s (${(verify / wireS).toFixed(2)}x), in all ${all.toFixed(2)} s (${(all / wireS).toFixed(2)}x)`,
    );
  }
}

if (import.meta.url === `file://${process.argv[1]}`) await flashBench();
