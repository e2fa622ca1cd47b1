// The Firmware view's entry: loaded on demand. The ESP's flash image replaces this file with
// firmware-view-absent.ts (app/vite.config.ts): the hub cannot flash itself, and its flash is for jobs.
export const FIRMWARE_VIEW = true;
export const loadFirmwarePanel = () => import('./FirmwarePanel.svelte');
