// What the ESP's flash image has in place of firmware-view.ts (vite --mode esp): no Firmware view.
export const FIRMWARE_VIEW = false;
export const loadFirmwarePanel = (): Promise<never> => Promise.reject(new Error('no Firmware view in the app served by the printer'));
