import { describe, expect, it } from 'vitest';
import { readKept } from './sim-snapshot';

const card = [['J-1.uvj', 'UVJ…'], ['CONFIG.TXT', 'speed.travel = 120\n']];
const checkpoint = { file: 'J-1.uvj', done: 12, stops: 40, boot: 3, fires: 12 };
const machine = { version: 1, checkpoint, eeprom: { 'speed.travel': '120' }, boots: 3, running: { pos: [20000, 20050, 0], atMs: 1_700_000_000_000, speed: 4 } };

describe('readKept', () => {
  it('starts a new printer, without a note, when nothing was ever kept', () => {
    expect(readKept(undefined, undefined)).toEqual({ saved: null, running: null, note: null });
  });

  it('reads back a card, a checkpoint, the EEPROM, the start count and a running job', () => {
    expect(readKept(card, machine)).toEqual({
      saved: { files: card, checkpoint, eeprom: { 'speed.travel': '120' }, boots: 3 },
      running: machine.running,
      note: null,
    });
  });

  it('takes a card without a machine record, and a machine record without a card but its checkpoint', () => {
    expect(readKept(card, undefined)).toEqual({ saved: { files: card, checkpoint: null, eeprom: null, boots: 0 }, running: null, note: null });
    const k = readKept(undefined, { ...machine, checkpoint: null, running: null });
    expect(k.saved).toEqual({ files: [], checkpoint: null, eeprom: { 'speed.travel': '120' }, boots: 3 });
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
    const k = readKept(bad, { ...machine, checkpoint: null, running: null });
    expect(k.saved?.files).toEqual([]);
    expect(k.saved?.eeprom).toEqual({ 'speed.travel': '120' });
    expect(k.note).toMatch(/^The simulated printer kept in this browser was damaged: its card could not be read/);
  });

  // Each damaged machine record gives the defaults and nothing to resume; the card stays.
  it.each([
    ['of another version', { ...machine, version: 2 }],
    ['without a start count', { ...machine, boots: -1 }],
    ['with a checkpoint past its end', { ...machine, checkpoint: { ...checkpoint, done: 41 } }],
    ['with a checkpoint missing a field', { ...machine, checkpoint: { file: 'J-1.uvj', done: 1, stops: 2, boot: 1 } }],
    ['with a setting out of range', { ...machine, eeprom: { 'speed.travel': '9000' } }],
    ['with an unknown setting', { ...machine, eeprom: { 'laser.power': '1' } }],
    ['with a running job at no place', { ...machine, running: { ...machine.running, pos: [1, 2] } }],
    ['with a running job at speed 0', { ...machine, running: { ...machine.running, speed: 0 } }],
    ['that is a list', [machine]],
  ])('drops a machine record %s', (_what, bad) => {
    const k = readKept(card, bad);
    expect(k.saved).toEqual({ files: card, checkpoint: null, eeprom: null, boots: 0 });
    expect(k.running).toBeNull();
    expect(k.note).toMatch(/its settings and checkpoint could not be read, so it has its defaults and nothing to resume\.$/);
  });

  it('has nothing to resume when the checkpoint names a file the card does not hold', () => {
    const k = readKept([['OTHER.uvj', 'x']], machine);
    expect(k.saved?.checkpoint).toBeNull();
    expect(k.running).toBeNull();
    expect(k.saved?.boots).toBe(3);
    expect(k.note).toMatch(/its checkpoint names J-1\.uvj, which is not on its card, so there is nothing to resume\.$/);
  });

  it('says every loss in one note', () => {
    const k = readKept('garbage', { ...machine, version: 0 });
    expect(k.note).toMatch(/card could not be read.*; its settings and checkpoint could not be read/);
  });
});
