// What the app knows of Web Serial before the serial transport's code loads (when USB is chosen):
// whether this browser has it, and the picker closed without a port, which is not an error to show.

export function serialSupported(): boolean {
  return typeof navigator !== 'undefined' && ('serial' in navigator || 'usb' in navigator);
}

/** The user closed the port picker without choosing: not an error to show. */
export class PickerDismissed extends Error {}
