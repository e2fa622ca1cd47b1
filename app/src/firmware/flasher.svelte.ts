// The Firmware view's state: one flash at a time, from picking the port to the new firmware's answer.

import { NoSerialApi } from '../device/serial-support';
import { PickerDismissed, serialApi } from '../device/serial-transport';
import type { AvrBoard } from './chips';
import { FlashError, checkImage, flashAvr, type FlashFailure, type FlashProgress } from './flash-avr';
import { askVersion } from './firmware-version';
import type { EspBoard, EspPart } from './esp-flash';
import { SerialLink } from './serial-link';

export type FlashState =
  | { state: 'idle' }
  | { state: 'flashing'; progress: FlashProgress }
  | { state: 'starting' }
  | { state: 'done'; version: string; also: string[] }
  | { state: 'answered'; summary: string; lines: string[] }
  | { state: 'silent' }
  | { state: 'failed'; failure: FlashFailure | 'port' | 'browser'; message: string };

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
      this.state = !answer ? { state: 'silent' } : 'version' in answer ? { state: 'done', ...answer } : { state: 'answered', ...answer };
    } catch (e) {
      this.#fail(e);
    } finally {
      await link?.close();
    }
  }

  /** The Wi-Fi hub: its firmware and the LittleFS image holding the app, through esptool-js. */
  async flashEsp(board: EspBoard, parts: EspPart[], version: string): Promise<void> {
    let port: SerialPort;
    try {
      port = await (await serialApi()).requestPort();
    } catch (e) {
      if ((e as Error).name === 'NotFoundError' || e instanceof PickerDismissed) return;
      this.#fail(e);
      return;
    }
    try {
      this.state = { state: 'flashing', progress: { phase: 'connecting' } };
      const { flashEsp } = await import('./esp-flash');
      const chip = await flashEsp(port, board, parts, (progress) => (this.state = { state: 'flashing', progress }));
      this.state = { state: 'done', version: `${version} on the ${chip}`, also: ['set DIP switches 1 and 2 ON (the others OFF) and open the hub\'s page to check it'] };
    } catch (e) {
      this.#fail(e);
    }
  }

  /** One message per cause: a flash that failed, a browser without serial access, a port in use. */
  #fail(e: unknown): void {
    if (e instanceof FlashError) this.state = { state: 'failed', failure: e.failure, message: e.message };
    else if (e instanceof NoSerialApi) this.state = { state: 'failed', failure: 'browser', message: e.message };
    else {
      const why = (e as Error).message.replace(/\.$/, '');
      this.state = { state: 'failed', failure: 'port', message: `The port could not be used (${why}). Close any other program using it (Arduino IDE, a serial monitor, this app's own connection) and try again.` };
    }
  }
}
