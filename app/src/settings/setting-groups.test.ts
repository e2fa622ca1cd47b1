import { describe, expect, it } from 'vitest';
import { CONFIG_DEFAULTS } from '../machine/config';
import { settingGroups } from './setting-groups';

describe('settingGroups', () => {
  it('puts every key in one group, in a fixed order, keeping the printer order within a group', () => {
    const keys = Object.keys(CONFIG_DEFAULTS);
    const groups = settingGroups(keys);
    expect(groups.map((g) => g.name)).toEqual(['Bed', 'Motion', 'LEDs', 'Thermal', 'Probe and mesh', 'Other']);
    expect(groups.flatMap((g) => g.keys).sort()).toEqual([...keys].sort());
    expect(groups[0].keys).toEqual(['bed.x', 'bed.y', 'bed.z', 'pitch.x', 'pitch.y']);
    expect(groups.at(-1)!.keys).toEqual(['esp.port', 'light.pin', 'report.position_ms']);
  });
});
