import { describe, expect, it } from 'vitest';
import { readKept } from './sim-snapshot';
import { EEPROM_BYTES } from './wasm/printer-module';

const card = [['J-1.uvj', 'UVJ…'], ['JOB~CKP', 'checkpoint bytes'], ['CONFIG.TXT', 'speed.travel = 120\n']];
const eeprom = new Uint8Array(EEPROM_BYTES).fill(0xff);
eeprom[0] = 0x55;
const machine = { version: 2, eeprom, boots: 3, running: { atMs: 1_700_000_000_000, speed: 4, paced: false } };

describe('readKept', () => {
  it('starts a new printer, without a note, when nothing was ever kept', () => {
    expect(readKept(undefined, undefined)).toEqual({ saved: null, running: null, note: null });
  });

  it('reads back a card (the checkpoint on it), the EEPROM, the start count and a running job', () => {
    expect(readKept(card, machine)).toEqual({ saved: { files: card, eeprom, boots: 3 }, running: machine.running, note: null });
  });

  it('takes a card without a machine record, and a machine record without a card, which runs nothing on', () => {
    expect(readKept(card, undefined)).toEqual({ saved: { files: card, eeprom: null, boots: 0 }, running: null, note: null });
    const k = readKept(undefined, machine);
    expect(k.saved).toEqual({ files: [], eeprom, boots: 3 });
    expect(k.running).toBeNull();
    expect(k.note).toBeNull();
  });

  // Each damaged card starts an empty card, keeps the rest, and says so.
  it.each([
    ['not a list', { files: card }],
    ['a file without a body', [['J-1.uvj']]],
    ['a body that is not text', [['J-1.uvj', 42]]],
    ['a file without a name', [['', 'x']]],
    ['a string', 'J-1.uvj'],
    ['null', null],
  ])('empties a card that is %s', (_what, bad) => {
    const k = readKept(bad, { ...machine, running: null });
    expect(k.saved?.files).toEqual([]);
    expect(k.saved?.eeprom).toEqual(eeprom);
    expect(k.note).toMatch(/^The simulated printer kept in this browser was damaged: its card could not be read/);
  });

  // Each damaged machine record gives the defaults and nothing to run on; the card stays.
  it.each([
    ['of another version', { ...machine, version: 3 }],
    ['without a start count', { ...machine, boots: -1 }],
    ['with a start count past the Nano\'s counter', { ...machine, boots: 70000 }],
    ['with a short EEPROM', { ...machine, eeprom: new Uint8Array(100) }],
    ['with an EEPROM that is not bytes', { ...machine, eeprom: Array.from(eeprom) }],
    ['with a running job at speed 0', { ...machine, running: { ...machine.running, speed: 0 } }],
    ['with a running job without its pacing', { ...machine, running: { atMs: 1, speed: 1 } }],
    ['that is a list', [machine]],
  ])('drops a machine record %s', (_what, bad) => {
    const k = readKept(card, bad);
    expect(k.saved).toEqual({ files: card, eeprom: null, boots: 0 });
    expect(k.running).toBeNull();
    expect(k.note).toMatch(/its settings and checkpoint could not be read, so it has its defaults and nothing to resume\.$/);
  });

  it('says so when the record was kept by the printer before the firmware ran in the browser', () => {
    const k = readKept(card, { version: 1, checkpoint: null, eeprom: { 'speed.travel': '120' }, boots: 3, running: null });
    expect(k.saved).toEqual({ files: card, eeprom: null, boots: 0 });
    expect(k.note).toMatch(/kept by an earlier version of the simulated printer/);
  });
});
