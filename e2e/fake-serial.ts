// Test-only: replaces navigator.serial with a port whose bytes are answered in Node, as the Mega would.
import type { Page } from '@playwright/test';

export interface SerialPeer {
  /** Bytes the page wrote to the port. */
  receive(bytes: string): void;
  /** The page opened the port at this baud (a real Mega resets then). */
  open?(baud: number): void;
  /** The page set the port's control lines (DTR low then high resets an Arduino through its capacitor). */
  signals?(s: { dataTerminalReady?: boolean; requestToSend?: boolean }): void;
}

export interface FakeSerial {
  /** Sends bytes to the page as if the device wrote them. */
  push(bytes: string): Promise<void>;
  /** The USB device vanishes: the port's reader fails with a NetworkError, as Chromium does. */
  lose(): Promise<void>;
  /** Everything the page wrote, as text. */
  written(): string;
}

/**
 * Installs the fake before any page script runs. `pick` decides what requestPort() does:
 * 'port' hands out the fake port, 'dismiss' behaves like a closed picker.
 */
export async function installFakeSerial(page: Page, peer: (fake: FakeSerial) => SerialPeer, pick: 'port' | 'dismiss' = 'port', bauds: number[] = [115200]): Promise<FakeSerial> {
  let written = '';
  let chain = Promise.resolve();
  // Bytes wait here while a delivery is under way and go together in the next: one page.evaluate
  // per chunk falls behind a printer that reports many lines a second at a raised simulation speed.
  let pending = '';
  const deliver = () => {
    const codes = Array.from(pending, (c) => c.charCodeAt(0));
    pending = '';
    // After the test ends the page is gone; the printer may still be talking.
    return page.evaluate((b) => (window as unknown as { __serialRx(b: number[]): void }).__serialRx(b), codes).catch(() => {});
  };
  const fake: FakeSerial = {
    push(bytes) {
      if (!pending) chain = chain.then(deliver);
      pending += bytes;
      return chain;
    },
    written: () => written,
    lose() {
      chain = chain.then(() => page.evaluate(() => (window as unknown as { __serialLost(): void }).__serialLost()));
      return chain;
    },
  };
  const device = peer(fake);
  await page.exposeBinding('__serialOpen', (_source, baud: number) => device.open?.(baud));
  await page.exposeBinding('__serialSignals', (_source, lines: { dataTerminalReady?: boolean; requestToSend?: boolean }) => device.signals?.(lines));
  await page.exposeBinding('__serialTx', (_source, codes: number[]) => {
    const text = String.fromCharCode(...codes);
    written += text;
    device.receive(text);
  });
  await page.addInitScript(({ mode, bauds }) => {
    const w = window as unknown as {
      __serialTx(b: number[]): Promise<void>;
      __serialOpen(baud: number): Promise<void>;
      __serialSignals(lines: object): Promise<void>;
      __serialRx(b: number[]): void;
      __serialLost(): void;
    };
    w.__serialRx = () => {}; // bytes before the port opens are lost, as on a real port
    w.__serialLost = () => {};
    class FakePort extends EventTarget {
      readable: ReadableStream<Uint8Array> | null = null;
      writable: WritableStream<Uint8Array> | null = null;
      async open(options: { baudRate: number }) {
        if (!bauds.includes(options.baudRate)) throw new Error(`unexpected baud rate ${options.baudRate}`);
        this.readable = new ReadableStream({
          start(controller) {
            let lost = false;
            w.__serialRx = (bytes) => {
              if (!lost) controller.enqueue(new Uint8Array(bytes)); // a lost device sends nothing more
            };
            w.__serialLost = () => {
              lost = true;
              controller.error(new DOMException('The device has been lost.', 'NetworkError'));
            };
          },
        });
        this.writable = new WritableStream({
          async write(chunk) {
            await w.__serialTx(Array.from(chunk));
          },
        });
        await w.__serialOpen(options.baudRate);
      }
      async setSignals(lines: object) {
        await w.__serialSignals(lines);
      }
      async close() {
        this.readable = null;
        this.writable = null;
      }
      getInfo() {
        return { usbVendorId: 0x2341, usbProductId: 0x0042 };
      }
    }
    const serial = Object.assign(new EventTarget(), {
      async requestPort() {
        if (mode === 'dismiss') throw new DOMException('No port selected by the user.', 'NotFoundError');
        return new FakePort();
      },
      async getPorts() {
        return [];
      },
    });
    Object.defineProperty(navigator, 'serial', { value: serial, configurable: true });
  }, { mode: pick, bauds });
  return fake;
}
