// What the app knows of Web Serial before the serial transport's code loads (when USB is chosen):
// whether this browser has it and, where it does not, why; and the picker closed without a port, which
// is not an error to show.

export type SerialAccess = 'web-serial' | 'webusb' | 'none';

/** Web Serial itself, the WebUSB polyfill's stand-in (Chrome on Android), or nothing at all. */
export function serialAccess(nav: object | undefined = typeof navigator === 'undefined' ? undefined : navigator): SerialAccess {
  if (!nav) return 'none';
  if ('serial' in nav) return 'web-serial';
  if ('usb' in nav) return 'webusb';
  return 'none';
}

export function serialSupported(): boolean {
  return serialAccess() !== 'none';
}

/** Why USB cannot be used at all: Firefox, Safari and every browser on iOS have neither API. */
export const NO_SERIAL_REASON =
  'This browser has no Web Serial: Firefox and Safari do not offer it, nor does any browser on an iPhone or iPad. Use Chrome or Edge on a desktop computer.';

/** What WebUSB cannot reach: the polyfill drives only CDC-ACM USB chips; CH340 and FTDI need a driver it cannot be. */
export const WEBUSB_LIMIT =
  'This browser reaches USB boards only through WebUSB, which lists boards whose USB chip is a CDC-ACM one (the Mega\'s ATmega16U2). A Nano with a CH340 or FTDI chip never appears: flash and connect it from Chrome or Edge on a desktop computer.';

/** The note to show beside the USB choice, or null where Web Serial is there. */
export function serialNote(access: SerialAccess = serialAccess()): string | null {
  return access === 'none' ? NO_SERIAL_REASON : access === 'webusb' ? WEBUSB_LIMIT : null;
}

/** This browser has neither Web Serial nor WebUSB: its message is the whole story. */
export class NoSerialApi extends Error {
  constructor() {
    super(NO_SERIAL_REASON);
  }
}

/** The user closed the port picker without choosing: not an error to show. */
export class PickerDismissed extends Error {}
