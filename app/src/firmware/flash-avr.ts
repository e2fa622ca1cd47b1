// Flashing an AVR board over its bootloader: check the image, check the chip, write every page, read
// every page back. Each way it can fail is a FlashError saying what happened and what to do.

import { LinkLost, LinkTimeout, type ByteLink } from './byte-link';
import { bootSectionBytes, chipBySignature, flashLimit, hexBytes, imageMismatch, type AvrBoard } from './chips';
import { ProtocolError, Stk500v1 } from './stk500v1';
import { Stk500v2 } from './stk500v2';

export type FlashFailure = 'image-too-big' | 'image-for-other-chip' | 'wrong-chip' | 'no-bootloader' | 'cable-pulled' | 'verify-failed' | 'protocol';

export class FlashError extends Error {
  constructor(readonly failure: FlashFailure, message: string) {
    super(message);
  }
}

export type FlashProgress = { phase: 'connecting' } | { phase: 'writing' | 'verifying'; done: number; total: number };

/** What a bootloader offers the flasher, whichever protocol it speaks. */
interface Bootloader {
  hello(): Promise<void>;
  signature(): Promise<Uint8Array>;
  enterProgramming(): Promise<void>;
  leaveProgramming(): Promise<void>;
  writePage(at: number, page: Uint8Array): Promise<void>;
  readPage(at: number, length: number): Promise<Uint8Array>;
}

function bootloaderOn(link: ByteLink, board: AvrBoard): Bootloader {
  if (board.protocol === 'stk500v1') {
    const v1 = new Stk500v1(link);
    return Object.assign(v1, { hello: () => v1.sync() });
  }
  const v2 = new Stk500v2(link);
  return Object.assign(v2, { hello: async () => void (await v2.signOn()) });
}

/**
 * Who is there when the board's bootloader did not answer: the other protocol's bootloader, asked for
 * its chip after a reset (the Optiboot a Mega's first message threw out has started the application).
 * Twice, each after its own reset, as avrdude resets before each sync attempt: on a slow host the first
 * question can come after Optiboot's second has run out.
 */
async function chipOfOtherBootloader(link: ByteLink, board: AvrBoard): Promise<Uint8Array | null> {
  if (!link.reset) return null;
  for (let attempt = 0; attempt < 2; attempt++) {
    try {
      await link.reset();
      if (board.protocol === 'stk500v2') {
        const v1 = new Stk500v1(link);
        await v1.sync();
        return await v1.signature();
      }
      const v2 = new Stk500v2(link);
      await v2.signOn();
      return await v2.signature();
    } catch (e) {
      if (!(e instanceof LinkTimeout || e instanceof ProtocolError)) return null;
    }
  }
  return null;
}

function wrongChip(board: AvrBoard, signature: Uint8Array): FlashError {
  const chip = chipBySignature(signature);
  const what = chip ? `an ${chip.name}` : `a chip with signature ${hexBytes(signature)}`;
  return new FlashError('wrong-chip', `The board on this port has ${what}, not the ${board.chip.name} of the ${board.name}. Nothing was written. Pick the board that is plugged in, or plug in the ${board.name}.`);
}

/** Refuses an image that cannot go on this board, before the port is even opened. */
export function checkImage(board: AvrBoard, bytes: Uint8Array): void {
  const mismatch = imageMismatch(board.chip, bytes);
  if (mismatch) {
    throw new FlashError('image-for-other-chip', `${mismatch}, and the ${board.name} has an ${board.chip.name}. Nothing was written. Pick the image built for this board.`);
  }
  const limit = flashLimit(board);
  if (bytes.length > limit) {
    // A real Nano's fuses keep 2 KB for the boot section whatever bootloader it has, and its lock bits
    // refuse writes there: past the limit, the flash would fail its read-back (boards.txt's maximum_size).
    throw new FlashError('image-too-big', `The image is ${bytes.length} B; the ${board.chip.name} takes ${limit} B below its ${bootSectionBytes(board)} B boot section. Pick the image built for this board.`);
  }
}

/** Writes `bytes` from address 0 and reads them back. The bootloader must already be listening (just reset). */
export async function flashAvr(link: ByteLink, board: AvrBoard, bytes: Uint8Array, progress: (p: FlashProgress) => void = () => {}): Promise<void> {
  checkImage(board, bytes);
  const boot = bootloaderOn(link, board);
  const page = board.chip.pageBytes;
  const pages = Math.ceil(bytes.length / page);
  const pageAt = (i: number) => {
    const p = new Uint8Array(page).fill(0xff);
    p.set(bytes.subarray(i * page, (i + 1) * page));
    return p;
  };
  let writing = -1;
  try {
    progress({ phase: 'connecting' });
    try {
      await boot.hello();
    } catch (e) {
      if (!(e instanceof LinkTimeout || e instanceof ProtocolError) || !link.reset) throw e;
      // Once more after another reset: a bootloader that met a broken message before it was in step
      // leaves for the application (Optiboot through its watchdog), and only a reset brings it back.
      try {
        await link.reset();
        await boot.hello();
      } catch (again) {
        if (!(again instanceof LinkTimeout || again instanceof ProtocolError)) throw again;
        const other = await chipOfOtherBootloader(link, board);
        throw other ? wrongChip(board, other) : again;
      }
    }
    const signature = await boot.signature();
    if (chipBySignature(signature) !== board.chip) throw wrongChip(board, signature);
    await boot.enterProgramming();
    for (writing = 0; writing < pages; writing++) {
      await boot.writePage(writing * page, pageAt(writing));
      progress({ phase: 'writing', done: writing + 1, total: pages });
    }
    writing = -1;
    for (let i = 0; i < pages; i++) {
      const back = await boot.readPage(i * page, page);
      const expected = pageAt(i);
      const at = back.findIndex((b, k) => b !== expected[k]);
      if (at >= 0) {
        throw new FlashError('verify-failed', `Reading the flash back, byte 0x${(i * page + at).toString(16)} is 0x${hexBytes([back[at]])}, not 0x${hexBytes([expected[at]])}. The bootloader is still in place: flash again.`);
      }
      progress({ phase: 'verifying', done: i + 1, total: pages });
    }
    await boot.leaveProgramming();
  } catch (e) {
    if (e instanceof FlashError) throw e;
    if (e instanceof LinkLost || (e instanceof LinkTimeout && writing >= 0)) {
      const where = writing >= 0 ? ` while writing page ${writing + 1} of ${pages}` : '';
      throw new FlashError('cable-pulled', `The board stopped answering${where}: the cable was pulled, or the board lost power. Its bootloader sits in a section that writing the firmware never touches, so it is still there; only the firmware is incomplete. Plug the board back in and flash again.`);
    }
    if (e instanceof LinkTimeout) {
      throw new FlashError('no-bootloader', `No bootloader answered at ${board.baud} baud. Check that the ${board.name} is plugged in and that you picked its port${board.id === 'nano' ? '; a Nano bought before 2018 may have the old bootloader (57600 baud): pick "Nano, old bootloader"' : ''}${board.id === 'nano-old' ? '; a newer Nano has Optiboot (115200 baud): pick "Nano, Optiboot"' : ''}.`);
    }
    throw new FlashError('protocol', `The bootloader answered unexpectedly (${(e as Error).message}). Press the board's reset button and flash again.`);
  }
}
