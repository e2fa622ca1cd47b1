// The Firmware view's state: one flash at a time, from picking the port to the new firmware's answer.

import { PickerDismissed, serialApi } from '../device/serial-transport';
import type { AvrBoard } from './chips';
import { FlashError, checkImage, flashAvr, type FlashFailure, type FlashProgress } from './flash-avr';
import { askVersion } from './firmware-version';
import { SerialLink } from './serial-link';

export type FlashState =
  | { state: 'idle' }
  | { state: 'flashing'; progress: FlashProgress }
  | { state: 'starting' }
  | { state: 'done'; version: string; also: string[] }
  | { state: 'silent' }
  | { state: 'failed'; failure: FlashFailure | 'port'; message: string };

export class Flasher {
  state = $state<FlashState>({ state: 'idle' });
  readonly busy = $derived(this.state.state === 'flashing' || this.state.state === 'starting');

  async flash(board: AvrBoard, bytes: Uint8Array): Promise<void> {
    try {
      checkImage(board, bytes); // before the picker: a wrong image needs no board
    } catch (e) {
      this.#fail(e);
      return;
    }
    let port: SerialPort;
    try {
      port = await (await serialApi()).requestPort();
    } catch (e) {
      if ((e as Error).name === 'NotFoundError' || e instanceof PickerDismissed) return; // no port picked: nothing to say
      this.#fail(e);
      return;
    }
    let link: SerialLink | null = null;
    try {
      this.state = { state: 'flashing', progress: { phase: 'connecting' } };
      link = await SerialLink.open(port, board.baud);
      await link.reset();
      await flashAvr(link, board, bytes, (progress) => (this.state = { state: 'flashing', progress }));
      await link.close();
      link = null;
      // Reopened at the firmware's baud, the board resets: its bootloader waits, then the new firmware runs.
      this.state = { state: 'starting' };
      link = await SerialLink.open(port, board.firmwareBaud);
      await link.reset();
      const answer = await askVersion(link, board);
      this.state = answer ? { state: 'done', ...answer } : { state: 'silent' };
    } catch (e) {
      this.#fail(e);
    } finally {
      await link?.close();
    }
  }

  #fail(e: unknown): void {
    this.state = e instanceof FlashError
      ? { state: 'failed', failure: e.failure, message: e.message }
      : { state: 'failed', failure: 'port', message: `The port could not be used: ${(e as Error).message}. Close any other program using it (Arduino IDE, a serial monitor, this app's own connection) and try again.` };
  }
}
