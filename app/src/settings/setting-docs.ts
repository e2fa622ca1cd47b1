// What each setting is, for people: its name in words, unit, range and a one-line description, from
// the Mega's one table of settings (firmware/mega/settings.toml, generated into
// app/src/machine/settings-table.ts), and what is wrong with a value typed for it.

import { SETTINGS, type SettingRow } from '../machine/settings-table';

export type SettingDoc = SettingRow;

export const SETTING_DOCS: ReadonlyMap<string, SettingDoc> = new Map(SETTINGS.map((d) => [d.key, d]));

/** A setting that is on (1) or off (0), shown as a checkbox: the Reverse X/Y/Z pins. */
export function isToggle(doc: SettingDoc | undefined): boolean {
  return !!doc && doc.kind === 'whole' && doc.lo === 0 && doc.hi === 1;
}

/** What is wrong with `value` for `key`, in words, or null if the printer will take it (CONFIG.md "Values"). */
export function settingProblem(key: string, value: string, doc = SETTING_DOCS.get(key)): string | null {
  if (!doc) return 'not a setting this printer knows';
  const inRange = (v: number) => v >= doc.lo && v <= doc.hi;
  if (doc.kind === 'pair') {
    if (!/^-?\d+,-?\d+$/.test(value)) return 'two whole numbers with a comma, dx,dy';
    return value.split(',').every((v) => inRange(Number(v))) ? null : `each must be ${doc.lo} to ${doc.hi}`;
  }
  if (!/^-?\d+(\.\d+)?$/.test(value)) return 'not a number';
  const milli = Math.round(Number(value) * 1000); // kept in thousandths, as on the Mega
  if (doc.off && milli === 0) return null; // off
  if (!inRange(milli / 1000)) return `out of range: ${doc.off ? '0, or ' : ''}${doc.lo} to ${doc.hi}`;
  if (doc.kind === 'whole' && milli % 1000 !== 0) return 'a whole number';
  return null;
}
