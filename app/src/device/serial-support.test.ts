import { describe, expect, it } from 'vitest';
import { NO_SERIAL_REASON, WEBUSB_LIMIT, serialAccess, serialNote } from './serial-support';

describe('what a browser offers for USB, and why not', () => {
  it('has Web Serial in desktop Chrome and Edge: nothing to say', () => {
    expect(serialAccess({ serial: {}, usb: {} })).toBe('web-serial');
    expect(serialNote('web-serial')).toBeNull();
  });

  it('says to use Chrome or Edge on a desktop where there is neither (Firefox, Safari)', () => {
    expect(serialAccess({})).toBe('none');
    expect(serialNote('none')).toBe(NO_SERIAL_REASON);
    expect(NO_SERIAL_REASON).toMatch(/Firefox and Safari.*Chrome or Edge on a desktop/);
  });

  it('says that CH340 and FTDI boards cannot be reached over WebUSB (Android Chrome)', () => {
    expect(serialAccess({ usb: {} })).toBe('webusb');
    expect(serialNote('webusb')).toBe(WEBUSB_LIMIT);
    expect(WEBUSB_LIMIT).toMatch(/CH340 or FTDI chip never appears/);
  });
});
